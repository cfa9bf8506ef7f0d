/* inertia-kit review page: draws the scene of <script id="scene-data"> (the contract of
 * inertia_kit/view/scene.py) with three.js. Z is up, as in URDF: the camera's up is +z, so the
 * robot's frames are used as they are. Everything the tests read is in the DOM:
 * #page-errors (errors, empty when none), body[data-ready="1"] after the first frame, and
 * #projected: each box's centre and screen rectangle in CSS pixels, and whether its link is
 * shown, as JSON. Which box is whose: the link's name on hover (#hover-label) and on selection
 * (#selection-label); the selected link's boxes stand out, the others dim; #tools isolates it
 * (only its link shown), shows all again, or fits the view to what is shown. */
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

  // name -> {record, group, visuals: [mesh], boxes: [{kind, object, edges}], markers, anchor,
  // card, toggle}
  var links = new Map();
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
      line.transparent = true; // dimmed while another link is selected
      [faces, edges].forEach(function (object) {
        object.matrixAutoUpdate = false;
        object.matrix.copy(boxMatrix(inertia));
        object.userData = { link: entry.record.name, kind: kind };
        entry.group.add(object);
      });
      entry.boxes.push({ kind: kind, object: faces, edges: edges });
      pickable.push(faces);
    }
    var dot = new THREE.Mesh(marker, new THREE.MeshBasicMaterial({ color: colour, transparent: true }));
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
    // anchor: where its name is pinned, in its frame: the declared COM, else the centroid
    var inertia = record.declared || record.geometry;
    var anchor = inertia && inertia.com.every(function (v) { return v !== null; })
      ? new THREE.Vector3(inertia.com[0], inertia.com[1], inertia.com[2]) : new THREE.Vector3();
    var entry = { record: record, group: group, visuals: [], boxes: [], markers: [], anchor: anchor };
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

  var cards = InertiaKitPanel.fill(panel, scene, {
    select: function (name) { select(name, true); },
    show: function (name, on) { show(name, on); },
    hover: function (name) { hover(name, null); },
  });
  scene.links.forEach(function (record) {
    var entry = links.get(record.name);
    entry.card = cards.get(record.name);
    entry.toggle = entry.card.querySelector("input.shown");
  });

  // --- which box is whose: labels, selection, isolate -----------------------------------------

  var selected = null; // a link's name
  var hovered = null; // {name, at: [x, y] in the view, or null: at the link's anchor}
  var hoverLabel = element("div", { id: "hover-label", class: "label" });
  var selectionLabel = element("div", { id: "selection-label", class: "label selection" });
  hoverLabel.hidden = selectionLabel.hidden = true;
  view.appendChild(hoverLabel);
  view.appendChild(selectionLabel);

  var KINDS = { declared: "declared inertia", geometry: "geometry's inertia", visual: "visual geometry" };

  // every material as the selection and the hover want it: the selected link's boxes and
  // skin stand out, every other link's dim; the hovered link's boxes a little stronger
  function look() {
    links.forEach(function (entry, name) {
      var error = entry.record.worst === "error";
      var chosen = name === selected, dim = selected !== null && !chosen;
      var over = hovered !== null && hovered.name === name;
      entry.card.classList.toggle("selected", chosen);
      entry.card.classList.toggle("hovered", over);
      entry.visuals.forEach(function (mesh) {
        mesh.material.opacity = chosen ? 0.6 : dim ? 0.1 : error ? 0.4 : 0.28;
        mesh.material.emissive.setHex(chosen ? 0x335577 : error ? 0x551010 : 0);
      });
      entry.boxes.forEach(function (box) {
        box.object.material.opacity = chosen || over ? 0.5 : dim ? 0.08 : 0.35;
        box.edges.material.opacity = dim && !over ? 0.25 : 1;
        // the hovered link's boxes outlined in white: which boxes the label names
        box.edges.material.color.setHex(over ? 0xffffff : COLOURS[box.kind]);
      });
      entry.markers.forEach(function (dot) { dot.material.opacity = dim && !over ? 0.3 : 1; });
    });
  }

  // a link's anchor on the screen, in the view's pixels (null: behind the camera)
  function onScreen(entry) {
    var point = entry.anchor.clone().applyMatrix4(entry.group.matrixWorld).project(camera);
    if (point.z > 1 || point.z < -1) return null;
    return [((point.x + 1) / 2) * view.clientWidth, ((1 - point.y) / 2) * view.clientHeight];
  }

  function place(label, entry, at, text) {
    var where = at || (entry.group.visible ? onScreen(entry) : null);
    label.hidden = where === null;
    if (where === null) return;
    label.textContent = InertiaKitPanel.shown(text);
    label.style.left = where[0] + "px";
    label.style.top = where[1] + "px";
    label.classList.toggle("at-cursor", !!at);
  }

  // the labels where the links are now (after every frame: the camera or a joint moved)
  function labels() {
    var entry = selected === null ? null : links.get(selected);
    if (entry) place(selectionLabel, entry, null, selected);
    else selectionLabel.hidden = true;
    var over = hovered === null ? null : links.get(hovered.name);
    // the selected link already has its name on the screen, at its anchor
    if (over && !(hovered.at === null && hovered.name === selected)) {
      place(hoverLabel, over, hovered.at, hovered.name + (hovered.kind ? ": " + KINDS[hovered.kind] : ""));
    } else {
      hoverLabel.hidden = true;
    }
  }

  function hover(name, at, kind) {
    var same = hovered === null ? name === null
      : name === hovered.name && kind === hovered.kind && (at === null) === (hovered.at === null);
    hovered = name === null ? null : { name: name, at: at, kind: kind || null };
    if (!same) look();
    labels();
    requestRender();
  }

  function select(name, focus) {
    selected = name;
    look();
    var entry = name === null ? null : links.get(name);
    if (entry && focus) frame(boundsOf([entry]), 1.3);
    else if (entry) entry.card.scrollIntoView({ block: "nearest" });
    tools();
    labels();
    requestRender();
  }

  function show(name, on) {
    var entry = links.get(name);
    entry.group.visible = on;
    entry.toggle.checked = on;
    entry.card.classList.toggle("hidden-link", !on);
    tools();
    labels();
    requestRender();
  }

  function isolate() {
    if (selected === null) return;
    links.forEach(function (entry, name) { show(name, name === selected); });
    frame(boundsOf([links.get(selected)]), 1.3);
  }

  function showAll() {
    links.forEach(function (entry, name) { show(name, true); });
  }

  function shownEntries() {
    var out = [];
    links.forEach(function (entry) { if (entry.group.visible) out.push(entry); });
    return out;
  }

  // what entries draw, in the pose of the moment (empty ones: a small box at their frame)
  function boundsOf(entries) {
    var bounds = new THREE.Box3();
    entries.forEach(function (entry) {
      var parts = entry.visuals.concat(entry.boxes.map(function (b) { return b.object; })).concat(entry.markers);
      var own = new THREE.Box3();
      parts.forEach(function (o) { own.expandByObject(o); });
      if (own.isEmpty()) own.setFromCenterAndSize(new THREE.Vector3().setFromMatrixPosition(entry.group.matrixWorld), new THREE.Vector3(0.1, 0.1, 0.1));
      bounds.union(own);
    });
    return bounds;
  }

  function fit() {
    var entries = shownEntries();
    if (entries.length) frame(boundsOf(entries), 1.15);
    requestRender();
  }

  var isolateButton = element("button", { type: "button", id: "isolate", text: "isolate", title: "show only the selected link (key I)" });
  var showAllButton = element("button", { type: "button", id: "show-all", text: "show all", title: "show every link again (key A)" });
  var fitButton = element("button", { type: "button", id: "fit", text: "fit", title: "fit the view to the links shown (key F)" });
  var status = element("span", { class: "status" });
  isolateButton.addEventListener("click", isolate);
  showAllButton.addEventListener("click", showAll);
  fitButton.addEventListener("click", fit);
  view.appendChild(element("div", { id: "tools" }, [isolateButton, showAllButton, fitButton, status]));

  // the toolbar as the selection and the hidden links are
  function tools() {
    var count = shownEntries().length;
    isolateButton.disabled = selected === null;
    showAllButton.disabled = count === links.size;
    status.textContent = selected === null
      ? "hover a box for its link; click to select"
      : InertiaKitPanel.shown(selected) + " selected";
    if (count !== links.size) status.textContent += " · " + count + " of " + links.size + " links shown";
  }

  window.addEventListener("keydown", function (event) {
    if (event.ctrlKey || event.metaKey || event.altKey || /^(INPUT|TEXTAREA|SELECT|BUTTON)$/.test(event.target.tagName)) return;
    var key = event.key.toLowerCase();
    if (key === "i") isolate();
    else if (key === "a") showAll();
    else if (key === "f") fit();
    else if (key === "escape") select(null, false);
  });

  // the link under the pointer: its name and what was hit, or null
  function pick(event) {
    var rect = renderer.domElement.getBoundingClientRect();
    var ndc = new THREE.Vector2(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
    var ray = new THREE.Raycaster();
    ray.setFromCamera(ndc, camera);
    var hits = ray.intersectObjects(pickable, false).filter(function (hit) {
      return links.get(hit.object.userData.link).group.visible; // a hidden link is not there
    });
    return hits.length ? hits[0].object.userData : null;
  }

  var pointer = null;
  renderer.domElement.addEventListener("pointerdown", function (event) { pointer = [event.clientX, event.clientY]; });
  renderer.domElement.addEventListener("pointerup", function (event) {
    if (!pointer || Math.abs(event.clientX - pointer[0]) + Math.abs(event.clientY - pointer[1]) > 4) return; // a drag
    var hit = pick(event);
    select(hit ? hit.link : null, false); // a click on nothing clears the selection
  });
  // a ray through every triangle costs: one pick per frame, at the pointer's last place
  var moved = null;
  function pickHover() {
    var event = moved;
    moved = null;
    if (event === null) return; // the pointer left first
    var hit = pick(event);
    var rect = view.getBoundingClientRect();
    if (hit) hover(hit.link, [event.clientX - rect.left, event.clientY - rect.top], hit.kind);
    else if (hovered !== null && hovered.at !== null) hover(null, null);
  }
  renderer.domElement.addEventListener("pointermove", function (event) {
    if (event.buttons) return; // turning the view
    if (moved === null) requestAnimationFrame(pickHover);
    moved = event;
  });
  renderer.domElement.addEventListener("pointerleave", function () {
    moved = null;
    if (hovered !== null && hovered.at !== null) hover(null, null);
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
          shown: links.get(record.name).group.visible,
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
    labels();
    if (document.body.dataset.ready !== "1") {
      document.body.dataset.firstFrameMs = String(Math.round(performance.now())); // since navigation
      document.body.dataset.ready = "1"; document.body.dataset.viewport = window.innerWidth + "x" + window.innerHeight;
    }
  }

  controls.addEventListener("change", requestRender);
  window.addEventListener("resize", resize);
  jointSliders();
  tools();
  resize(); // the aspect first: framing fits the narrower field of view
  frame(robotBounds, 1.15);
})();
