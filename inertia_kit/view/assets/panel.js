/* inertia-kit review page: the page's HTML elements and the side panel (each link's numbers and
 * findings), built with the DOM only (no markup strings: every name and message is text).
 * page.js, which draws the scene, uses it through the global InertiaKitPanel. */
var InertiaKitPanel = (function () {
  "use strict";

  // What inertia_kit/printable.py escapes in a terminal, escaped on the page too: a name that
  // holds a bidirectional control ("Trojan source") or a line break would otherwise reorder or
  // split what the reader sees. Keys (data-*) keep the exact text.
  var UNPRINTABLE = /[\u0000-\u001f\u007f-\u009f\u061c\u200e\u200f\u2028\u2029\u202a-\u202e\u2066-\u2069\ud800-\udfff]/gu;
  var NAMED = { "\n": "\\n", "\r": "\\r", "\t": "\\t" };

  function escaped(char) {
    if (NAMED[char] !== undefined) return NAMED[char];
    var code = char.charCodeAt(0);
    var hex = code.toString(16);
    return code < 0x100 ? "\\x" + ("0" + hex).slice(-2) : "\\u" + ("000" + hex).slice(-4);
  }

  function shown(text) {
    return String(text).replace(UNPRINTABLE, escaped);
  }

  function element(tag, attributes, children) {
    var node = document.createElement(tag);
    Object.keys(attributes || {}).forEach(function (key) {
      if (key === "text") node.textContent = shown(attributes[key]);
      else if (key === "title") node.setAttribute(key, shown(attributes[key]));
      else node.setAttribute(key, attributes[key]);
    });
    (children || []).forEach(function (child) { if (child) node.appendChild(child); });
    return node;
  }

  function legendRow(swatch, text) {
    return element("div", {}, [element("i", { class: swatch }), element("span", { text: text })]);
  }

  function legend() {
    return element("div", { id: "legend" }, [
      legendRow("swatch-declared", "declared inertia: equivalent box, ● COM"),
      legendRow("swatch-geometry", "geometry's inertia: equivalent box (dashed), ● centroid"),
      legendRow("swatch-visual", "visual geometry"),
      legendRow("swatch-error", "link with an error"),
    ]);
  }

  // four significant digits, as Python's "%.4g" (inertia_kit's fmt): 0.0002, 0.0076, 1273,
  // 5.729e-05; -0 and values below `negligible` as 0
  function number(value, unit, negligible) {
    if (value === null || value === undefined) return "—";
    var text;
    if (value === 0 || Math.abs(value) <= (negligible || 0)) text = "0";
    else if (Math.abs(value) < 1e-4 || Math.abs(value) >= 1e4) {
      var parts = value.toExponential(3).split("e");
      var exponent = parseInt(parts[1], 10);
      text = parts[0].replace(/\.?0+$/, "") + "e" + (exponent < 0 ? "-" : "+") + ("0" + Math.abs(exponent)).slice(-2);
    } else {
      text = value.toPrecision(4);
      if (text.indexOf(".") >= 0) text = text.replace(/\.?0+$/, "");
    }
    return unit ? text + " " + unit : text;
  }

  function row(label, value, kind) {
    return element("tr", {}, [element("td", { text: label }), element("td", { text: value, class: kind || "" })]);
  }

  // --- declared against geometry, in the link's axes ----------------------------------------

  // a cell is highlighted when its two values are more than DIFFERS of the link's scale apart:
  // of its mass, of its largest principal moment (every entry of the tensor), of its size
  // sqrt(trace / mass) (every coordinate of the COM); rounding (a product of 1e-16 against 0)
  // never is
  var DIFFERS = 0.01;
  // what shows as 0: a value below this fraction of the same scale, rounding noise (as
  // inertia_kit/physics/formatting.py's NEGLIGIBLE_PRODUCT in messages)
  var NEGLIGIBLE = 1e-6;
  var TENSOR = ["ixx", "iyy", "izz", "ixy", "ixz", "iyz"];

  function finite(value) { return typeof value === "number" && isFinite(value); }

  function largest(values) {
    return values.reduce(function (most, v) { return finite(v) ? Math.max(most, Math.abs(v)) : most; }, 0);
  }

  // the link's scales: of its mass, its moments and its lengths, over both records
  function scales(records) {
    var mass = 0, moment = 0, length = 0;
    records.forEach(function (r) {
      mass = Math.max(mass, largest([r.mass]));
      moment = Math.max(moment, largest(r.moments || []));
      var trace = (r.moments || []).reduce(function (sum, m) { return sum + m; }, 0);
      if (finite(trace) && finite(r.mass) && r.mass > 0 && trace > 0) length = Math.max(length, Math.sqrt(trace / r.mass));
      if (r.box) length = Math.max(length, largest(r.box));
    });
    records.forEach(function (r) { if (!length) length = largest(r.com || []); });
    return { mass: mass, moment: moment, length: length };
  }

  function differ(a, b, scale) {
    return finite(a) && finite(b) && Math.abs(a - b) > DIFFERS * scale;
  }

  // the text "0.0002 along x" of each principal moment (or box side), in moment order
  function principal(values, along, negligible) {
    return values.map(function (value, i) {
      var where = along && along[i];
      return number(value, "", negligible) + (where ? " along " + where : "");
    });
  }

  // the table's rows: [label, declared, geometry, differs], a cell a string or lines of text
  // (differs: one flag for the row, or one per line)
  function comparison(declared, geometry) {
    var both = [declared, geometry].filter(Boolean);
    var scale = scales(both);
    var tiny = { mass: NEGLIGIBLE * scale.mass, moment: NEGLIGIBLE * scale.moment, length: NEGLIGIBLE * scale.length };
    var rows = [];
    function scalar(label, read, which) {
      var d = declared ? read(declared) : null, g = geometry ? read(geometry) : null;
      rows.push({
        label: label, key: label,
        // a record that is not there: "none" once, in the first row
        cells: [
          declared ? number(d, "", tiny[which]) : rows.length ? "—" : "none",
          geometry ? number(g, "", tiny[which]) : rows.length ? "—" : "none",
        ],
        differs: differ(d, g, scale[which]),
      });
    }
    scalar("mass (kg)", function (r) { return r.mass; }, "mass");
    ["x", "y", "z"].forEach(function (axis, i) {
      scalar("COM " + axis + " (m)", function (r) { return r.com ? r.com[i] : null; }, "length");
    });
    rows.push({ heading: "inertia about the COM, kg·m²" });
    TENSOR.forEach(function (name) {
      // a scene without the tensor (an older one): the principal moments alone
      if (both.some(function (r) { return !r.tensor; })) return;
      scalar(name, function (r) { return r.tensor[name]; }, "moment");
    });
    function lines(label, read, which) {
      var d = declared && read(declared), g = geometry && read(geometry);
      if (!d && !g) return;
      var flags = [0, 1, 2].map(function (i) {
        if (!d || !g) return false;
        var da = declared.along && declared.along[i], ga = geometry.along && geometry.along[i];
        return differ(d[i], g[i], which === "moment" ? scale.moment : largest(d.concat(g))) || (!!da && !!ga && da !== ga);
      });
      rows.push({
        label: label, key: label,
        cells: [
          d ? principal(d, declared.along, which === "moment" ? tiny.moment : 0) : "—",
          g ? principal(g, geometry.along, which === "moment" ? tiny.moment : 0) : "—",
        ],
        differs: flags,
      });
    }
    lines("principal", function (r) { return r.moments; }, "moment");
    lines("box (m)", function (r) { return r.box; }, "length");
    return rows;
  }

  function cell(content, kind, flags) {
    var node = element("td", { class: kind });
    var many = Array.isArray(content);
    (many ? content : [content]).forEach(function (text, i) {
      var differs = Array.isArray(flags) ? flags[i] : flags;
      var line = element(many ? "div" : "span", { text: text, class: differs ? "differs" : "" });
      if (differs) line.setAttribute("title", "declared and geometry differ by more than " + DIFFERS * 100 + " % of the link's scale");
      node.appendChild(line);
    });
    var all = Array.isArray(flags) ? flags.some(Boolean) : flags;
    if (all) node.classList.add("differs");
    return node;
  }

  function note(text, kind) {
    return element("tr", { class: "note" }, [element("td", { text: text, colspan: "3", class: kind || "" })]);
  }

  function rotated(rpy) {
    return rpy && rpy.some(function (v) { return finite(v) && v !== 0; });
  }

  // declared and geometry side by side, in the link's axes, the cells that differ highlighted
  function inertiaTable(record) {
    var declared = record.declared, geometry = record.geometry;
    var rows = [element("tr", { class: "head" }, [
      element("th", { text: "link axes", title: "every value in the link's frame: its axes, its origin" }), element("th", { text: "declared", class: "declared" }),
      element("th", { text: "geometry", class: "geometry" }),
    ])];
    comparison(declared, geometry).forEach(function (line) {
      if (line.heading) {
        rows.push(element("tr", { class: "heading" }, [element("td", { text: line.heading, colspan: "3" })]));
        return;
      }
      rows.push(element("tr", { "data-row": line.key }, [
        element("td", { text: line.label }),
        cell(line.cells[0], "declared", line.differs),
        cell(line.cells[1], "geometry", line.differs),
      ]));
    });
    if (declared && rotated(declared.rpy)) {
      rows.push(note("declared: written in the axes of its <inertial>'s <origin rpy=\"" +
        declared.rpy.map(function (v) { return number(v); }).join(" ") + "\">, shown here in the link's", "declared"));
    }
    if (declared && declared.problem) rows.push(note("declared: " + declared.problem, "problem"));
    if (geometry && geometry.problem) rows.push(note("geometry: " + geometry.problem, "problem"));
    if (geometry && geometry.basis) rows.push(note("geometry: " + geometry.basis, "geometry"));
    return element("table", { class: "inertia" }, rows);
  }

  function findingItem(finding) {
    var where = finding.file
      ? finding.file + (finding.line ? ":" + finding.line : "") + (finding.column ? ":" + finding.column : "")
      : "";
    return element("li", {}, [
      element("span", { class: "code " + finding.severity, text: finding.code + " " }),
      element("span", { text: finding.message }),
      // the basis and arithmetic behind the one-line message, as inertia-lint's `detail:` line
      finding.detail ? element("div", { class: "detail", text: finding.detail }) : null,
      // what to do, as inertia-lint's `help:` line says it
      finding.help ? element("div", { class: "help", text: "help: " + finding.help }) : null,
      where ? element("div", { class: "where", text: where }) : null,
    ]);
  }

  function card(record, actions) {
    var shown = element("input", { type: "checkbox", class: "shown", title: "show this link in 3D" });
    shown.checked = true;
    shown.addEventListener("click", function (event) { event.stopPropagation(); });
    shown.addEventListener("change", function () { actions.show(record.name, shown.checked); });
    var heading = element("h2", {}, [element("span", { text: record.name, class: "name" })]);
    if (record.worst) heading.appendChild(element("span", { class: "badge " + record.worst, text: record.worst }));
    heading.appendChild(element("label", { class: "toggle", title: "show this link in 3D" }, [shown, element("span", { text: "shown" })]));
    heading.lastChild.addEventListener("click", function (event) { event.stopPropagation(); });
    var table = element("table", { class: "other" }, [].concat(
      [row("implied density", number(record.implied_density, "kg/m³"))],
      record.shown === "collision" ? [row("drawn", "collision geometry (no visual)")] : []
    ));
    var findings = element("ul", { class: "findings" }, (record.findings || []).map(findingItem));
    var classes = "link" + (record.worst ? " worst-" + record.worst : "");
    var node = element("div", { class: classes, "data-link": record.name }, [heading, inertiaTable(record), table, findings]);
    node.addEventListener("click", function () { actions.select(record.name); });
    node.addEventListener("mouseenter", function () { actions.hover(record.name); });
    node.addEventListener("mouseleave", function () { actions.hover(null); });
    return node;
  }

  // the panel's content; returns each link's card by name, a Map. actions: select(name) when a
  // card is clicked, show(name, on) when its "shown" box is ticked, hover(name or null)
  function fill(panel, scene, actions) {
    panel.appendChild(element("h1", { text: scene.robot + ": inertia review" }));
    panel.appendChild(element("div", { class: "file", text: scene.file }));
    if (scene.budget && scene.budget.decimated) {
      panel.appendChild(element("div", {
        class: "file",
        text: "meshes decimated for display to " + scene.budget.triangles + " triangles (mass properties use the originals)",
      }));
    }
    if ((scene.findings_elsewhere || []).length) {
      panel.appendChild(element("div", { class: "link" }, [
        element("h2", { text: "robot and joints" }),
        element("ul", { class: "findings" }, scene.findings_elsewhere.map(findingItem)),
      ]));
    }
    var cards = new Map(); // a link named "__proto__" is a name like any other
    scene.links.forEach(function (record) {
      var node = card(record, actions);
      cards.set(record.name, node);
      panel.appendChild(node);
    });
    return cards;
  }

  return { element: element, shown: shown, legend: legend, fill: fill, comparison: comparison };
})();
