/* inertia-kit review page: draws the scene of <script id="scene-data"> (the contract of
 * inertia_kit/view/scene.py) with three.js. Z is up, as in URDF: the camera's up is +z, so the
 * robot's frames are used as they are. Everything the tests read is in the DOM:
 * #page-errors (errors, empty when none), body[data-ready="1"] after the first frame, and
 * #projected: each box's centre and screen rectangle in CSS pixels, as JSON. */
(function () {
  "use strict";

  var COLOURS = {
    declared: 0xff8c1a, // orange: the declared inertia's equivalent box and its COM
    geometry: 0x18c6e6, // cyan: the geometry's equivalent box and its centroid
    visual: 0xb4b4b4, // grey: visual geometry
    error: 0xff3b30, // red: links whose worst finding is an error
  };
  // names and types come from the robot file: every table keyed by them is a Map (a name such
  // as "__proto__" or "constructor" is then a name like any other, never Object.prototype's)
  var MOVING = new Set(["revolute", "continuous", "prismatic"]);

  var scene = JSON.parse(document.getElementById("scene-data").textContent);

  // --- decoding ------------------------------------------------------------------------------

  function bytes(base64) {
    var text = atob(base64);
    var out = new Uint8Array(text.length);
    for (var i = 0; i < text.length; i++) out[i] = text.charCodeAt(i);
    return out.buffer;
  }

  function rowMajor(values) {
    var m = new THREE.Matrix4();
    m.set.apply(m, values); // Matrix4.set takes its arguments row by row
    return m;
  }

  function meshGeometry(mesh) {
    var geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(bytes(mesh.positions)), 3));
    geometry.setIndex(new THREE.BufferAttribute(new Uint32Array(bytes(mesh.indices)), 1));
    geometry.computeVertexNormals();
    geometry.computeBoundingSphere();
    return geometry;
  }

  // --- the page's elements (panel.js) ---------------------------------------------------------

  var element = InertiaKitPanel.element;
  var view = element("div", { id: "view" });
  var panel = element("div", { id: "panel" });
  var projected = element("pre", { id: "projected" });
  document.body.appendChild(view);
  document.body.appendChild(panel);
  document.body.appendChild(projected);
  view.appendChild(InertiaKitPanel.legend());

  // --- three.js set-up -----------------------------------------------------------------------

  var renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(0x1b1e23);
  view.appendChild(renderer.domElement);
  var world = new THREE.Scene();
  var camera = new THREE.PerspectiveCamera(45, 1, 0.001, 1000);
  camera.up.set(0, 0, 1);
  var controls = new THREE.OrbitControls(camera, renderer.domElement);
  world.add(new THREE.HemisphereLight(0xffffff, 0x404040, 2.2));
  var sun = new THREE.DirectionalLight(0xffffff, 1.5);
  sun.position.set(2, -3, 4);
  world.add(sun);

  var geometries = scene.meshes.map(meshGeometry);
  var unitBox = new THREE.BoxGeometry(1, 1, 1);
  var unitEdges = new THREE.EdgesGeometry(unitBox);
  var marker = new THREE.SphereGeometry(1, 16, 12);

  // --- links -----------------------------------------------------------------------------------

  var links = new Map(); // name -> {record, group, visuals: [mesh], boxes: [mesh], card}
  var pickable = []; // what a click in 3D can hit

  function visualMaterial(record, visual) {
    var error = record.worst === "error";
    var colour = error ? COLOURS.error : COLOURS.visual;
    if (!error && visual.color) colour = new THREE.Color(visual.color[0], visual.color[1], visual.color[2]);
    return new THREE.MeshStandardMaterial({
      color: colour,
      emissive: error ? 0x551010 : 0x000000,
      transparent: true,
      opacity: error ? 0.4 : 0.28,
      depthWrite: false,
      side: THREE.DoubleSide,
    });
  }

  // the frame of an equivalent box in its link: principal axes (a proper rotation), centred on
  // the COM, scaled to the box's sizes
  function boxMatrix(inertia) {
    var a = inertia.axes;
    var x = new THREE.Vector3(a[0], a[3], a[6]);
    var y = new THREE.Vector3(a[1], a[4], a[7]);
    var z = new THREE.Vector3(a[2], a[5], a[8]);
    if (x.clone().cross(y).dot(z) < 0) z.negate();
    var m = new THREE.Matrix4().makeBasis(x, y, z);
    m.scale(new THREE.Vector3(
      Math.max(inertia.box[0], 1e-6), Math.max(inertia.box[1], 1e-6), Math.max(inertia.box[2], 1e-6)));
    m.setPosition(inertia.com[0], inertia.com[1], inertia.com[2]);
    return m;
  }

  function addInertia(entry, inertia, kind, size) {
    if (!inertia) return;
    var colour = COLOURS[kind];
    if (inertia.box) {
      var faces = new THREE.Mesh(unitBox, new THREE.MeshBasicMaterial({
        color: colour, transparent: true, opacity: 0.35, depthWrite: false, side: THREE.DoubleSide,
      }));
      // the geometry's box dashed: where the two boxes coincide both colours still show
      var line = kind === "geometry"
        ? new THREE.LineDashedMaterial({ color: colour, dashSize: 0.06, gapSize: 0.06 })
        : new THREE.LineBasicMaterial({ color: colour });
      var edges = new THREE.LineSegments(unitEdges, line);
      if (kind === "geometry") edges.computeLineDistances();
      [faces, edges].forEach(function (object) {
        object.matrixAutoUpdate = false;
        object.matrix.copy(boxMatrix(inertia));
        object.userData = { link: entry.record.name, kind: kind };
        entry.group.add(object);
      });
      entry.boxes.push({ kind: kind, object: faces });
      pickable.push(faces);
    }
    var dot = new THREE.Mesh(marker, new THREE.MeshBasicMaterial({ color: colour }));
    dot.scale.setScalar(size);
    dot.position.set(inertia.com[0], inertia.com[1], inertia.com[2]);
    dot.userData = { link: entry.record.name, kind: kind };
    entry.group.add(dot);
    entry.markers.push(dot);
  }

  scene.links.forEach(function (record) {
    var group = new THREE.Group();
    group.matrixAutoUpdate = false;
    group.matrix.copy(rowMajor(record.world));
    world.add(group);
    var entry = { record: record, group: group, visuals: [], boxes: [], markers: [] };
    links.set(record.name, entry);
    (record.visuals || []).forEach(function (visual) {
      var geometry = geometries[visual.mesh];
      if (!geometry) return;
      var mesh = new THREE.Mesh(geometry, visualMaterial(record, visual));
      mesh.matrixAutoUpdate = false;
      mesh.matrix.copy(rowMajor(visual.transform));
      mesh.renderOrder = 1; // after the boxes: the robot's skin over its inertia
      mesh.userData = { link: record.name, kind: "visual" };
      group.add(mesh);
      entry.visuals.push(mesh);
      pickable.push(mesh);
    });
  });

  // markers sized to the robot: 1.2 % of its extent
  world.updateMatrixWorld(true);
  var robotBounds = new THREE.Box3();
  scene.links.forEach(function (record) {
    var entry = links.get(record.name);
    entry.visuals.forEach(function (mesh) { robotBounds.expandByObject(mesh); });
    [record.declared, record.geometry].forEach(function (inertia) {
      if (!inertia) return;
      var com = new THREE.Vector3(inertia.com[0], inertia.com[1], inertia.com[2]);
      robotBounds.expandByPoint(com.applyMatrix4(entry.group.matrixWorld));
    });
  });
  if (robotBounds.isEmpty()) robotBounds.set(new THREE.Vector3(-0.5, -0.5, -0.5), new THREE.Vector3(0.5, 0.5, 0.5));
  var extent = Math.max(robotBounds.getSize(new THREE.Vector3()).length(), 1e-3);
  scene.links.forEach(function (record) {
    var entry = links.get(record.name);
    addInertia(entry, record.declared, "declared", extent * 0.012);
    addInertia(entry, record.geometry, "geometry", extent * 0.012);
  });
  // Box3.expandByObject reads matrixWorld as it is: bring the new boxes' up to date first
  world.updateMatrixWorld(true);
  scene.links.forEach(function (record) {
    links.get(record.name).boxes.forEach(function (box) { robotBounds.expandByObject(box.object); });
  });

  // --- forward kinematics (joint sliders) ------------------------------------------------------

  var angles = new Map(); // joint name -> value
  var byName = new Map();
  scene.links.forEach(function (record) { byName.set(record.name, record); });

  function motion(joint, value) {
    var axis = new THREE.Vector3().fromArray(joint.axis || [1, 0, 0]);
    if (axis.lengthSq() === 0) axis.set(1, 0, 0);
    axis.normalize();
    if (joint.type === "prismatic") return new THREE.Matrix4().makeTranslation(axis.multiplyScalar(value));
    return new THREE.Matrix4().makeRotationAxis(axis, value);
  }

  function worldOf(name, memo) {
    if (memo.has(name)) return memo.get(name);
    var record = byName.get(name);
    var result;
    if (!record.joint || !record.parent || !byName.has(record.parent)) {
      result = rowMajor(record.world); // a root: its zero-pose frame
    } else {
      result = worldOf(record.parent, memo).clone().multiply(rowMajor(record.joint.origin));
      if (MOVING.has(record.joint.type)) result.multiply(motion(record.joint, angles.get(record.joint.name) || 0));
    }
    memo.set(name, result);
    return result;
  }

  function pose() {
    var memo = new Map();
    scene.links.forEach(function (record) { links.get(record.name).group.matrix.copy(worldOf(record.name, memo)); });
    world.updateMatrixWorld(true);
    requestRender();
  }

  function jointSliders() {
    var moving = scene.links.filter(function (r) { return r.joint && MOVING.has(r.joint.type); });
    if (!moving.length) return;
    // open when the sliders do not hide the robot (and the picture --png takes)
    var box = element("details", { id: "joints" }, [element("summary", { text: "joints (" + moving.length + ")" })]);
    box.open = moving.length <= 8;
    moving.forEach(function (record) {
      var joint = record.joint;
      var lower = joint.lower, upper = joint.upper;
      if (joint.type === "continuous" || lower === null || upper === null || !(upper > lower)) {
        if (joint.type === "prismatic") { lower = -extent / 2; upper = extent / 2; } else { lower = -Math.PI; upper = Math.PI; }
      }
      // the page opens in the zero pose: the range takes in 0 even where the limits do not
      lower = Math.min(lower, 0);
      upper = Math.max(upper, 0);
      angles.set(joint.name, 0);
      var value = element("span", { text: (0).toFixed(3) });
      var slider = element("input", {
        type: "range", min: String(lower), max: String(upper), step: String((upper - lower) / 500),
        value: "0", "data-joint": joint.name,
      });
      slider.addEventListener("input", function () {
        angles.set(joint.name, parseFloat(slider.value));
        value.textContent = angles.get(joint.name).toFixed(3);
        pose();
      });
      box.appendChild(element("label", { title: joint.name + " (" + joint.type + ")" }, [
        element("span", { text: joint.name }), slider, value,
      ]));
    });
    view.appendChild(box);
  }

  // --- side panel (panel.js) ------------------------------------------------------------------

  var cards = InertiaKitPanel.fill(panel, scene, function (name) { select(name, true); });
  scene.links.forEach(function (record) { links.get(record.name).card = cards.get(record.name); });

  // --- selection -------------------------------------------------------------------------------

  var selected = null;

  function highlight(name, on) {
    var entry = links.get(name);
    if (!entry) return;
    entry.card.classList.toggle("selected", on);
    entry.visuals.forEach(function (mesh) {
      mesh.material.opacity = on ? 0.6 : (entry.record.worst === "error" ? 0.4 : 0.28);
      mesh.material.emissive.setHex(on ? 0x335577 : (entry.record.worst === "error" ? 0x551010 : 0));
    });
  }

  function select(name, focus) {
    if (selected) highlight(selected, false);
    selected = name;
    highlight(name, true);
    var entry = links.get(name);
    if (focus) {
      var bounds = new THREE.Box3();
      entry.visuals.concat(entry.boxes.map(function (b) { return b.object; })).concat(entry.markers).forEach(function (o) { bounds.expandByObject(o); });
      if (bounds.isEmpty()) bounds.setFromCenterAndSize(new THREE.Vector3().setFromMatrixPosition(entry.group.matrixWorld), new THREE.Vector3(0.1, 0.1, 0.1));
      frame(bounds, 1.3);
    } else {
      entry.card.scrollIntoView({ block: "nearest" });
    }
    requestRender();
  }

  var pointer = null;
  renderer.domElement.addEventListener("pointerdown", function (event) { pointer = [event.clientX, event.clientY]; });
  renderer.domElement.addEventListener("pointerup", function (event) {
    if (!pointer || Math.abs(event.clientX - pointer[0]) + Math.abs(event.clientY - pointer[1]) > 4) return; // a drag
    var rect = renderer.domElement.getBoundingClientRect();
    var ndc = new THREE.Vector2(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
    var ray = new THREE.Raycaster();
    ray.setFromCamera(ndc, camera);
    var hits = ray.intersectObjects(pickable, false);
    if (hits.length) select(hits[0].object.userData.link, false);
  });

  // --- camera, rendering, what the tests read -------------------------------------------------

  function frame(bounds, margin) {
    var sphere = bounds.getBoundingSphere(new THREE.Sphere());
    var radius = Math.max(sphere.radius, 1e-3);
    var fov = (Math.min(camera.fov, camera.fov * camera.aspect) * Math.PI) / 360;
    var distance = (radius * margin) / Math.sin(fov);
    var direction = new THREE.Vector3(1, -1.4, 0.8).normalize();
    camera.position.copy(sphere.center).addScaledVector(direction, distance);
    camera.near = distance / 1000;
    camera.far = distance * 20;
    camera.updateProjectionMatrix();
    controls.target.copy(sphere.center);
    controls.update();
  }

  function resize() {
    var width = Math.max(view.clientWidth, 1), height = Math.max(view.clientHeight, 1);
    renderer.setSize(width, height, false);
    camera.aspect = width / height;
    camera.updateProjectionMatrix();
    requestRender();
  }

  function publishProjections() {
    var rect = renderer.domElement.getBoundingClientRect();
    function toX(ndc) { return rect.left + ((ndc + 1) / 2) * rect.width; }
    function toY(ndc) { return rect.top + ((1 - ndc) / 2) * rect.height; }
    var out = [];
    scene.links.forEach(function (record) {
      links.get(record.name).boxes.forEach(function (box) {
        var centre = new THREE.Vector3().setFromMatrixPosition(box.object.matrixWorld).project(camera);
        var screen = new THREE.Box2(); // the box's 8 corners on the screen
        for (var corner = 0; corner < 8; corner++) {
          var point = new THREE.Vector3((corner & 1) - 0.5, ((corner >> 1) & 1) - 0.5, ((corner >> 2) & 1) - 0.5);
          point.applyMatrix4(box.object.matrixWorld).project(camera);
          screen.expandByPoint(new THREE.Vector2(toX(point.x), toY(point.y)));
        }
        out.push({
          link: record.name, kind: box.kind,
          x: toX(centre.x), y: toY(centre.y),
          rect: [screen.min.x, screen.min.y, screen.max.x, screen.max.y],
          visible: Math.abs(centre.x) <= 1 && Math.abs(centre.y) <= 1 && centre.z < 1,
        });
      });
    });
    projected.textContent = JSON.stringify(out);
  }

  var pending = false;
  function requestRender() {
    if (pending) return;
    pending = true;
    requestAnimationFrame(draw);
  }

  function draw() {
    pending = false;
    renderer.render(world, camera);
    publishProjections();
    if (document.body.dataset.ready !== "1") {
      document.body.dataset.firstFrameMs = String(Math.round(performance.now())); // since navigation
      document.body.dataset.ready = "1"; document.body.dataset.viewport = window.innerWidth + "x" + window.innerHeight;
    }
  }

  controls.addEventListener("change", requestRender);
  window.addEventListener("resize", resize);
  jointSliders();
  resize(); // the aspect first: framing fits the narrower field of view
  frame(robotBounds, 1.15);
})();
