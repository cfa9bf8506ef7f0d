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

  function number(value, unit) {
    if (value === null || value === undefined) return "—";
    var big = Math.abs(value) >= 1e4 || (value !== 0 && Math.abs(value) < 1e-3);
    var text = big ? value.toExponential(3) : value.toPrecision(4);
    return unit ? text + " " + unit : text;
  }

  function row(label, value, kind) {
    return element("tr", {}, [element("td", { text: label }), element("td", { text: value, class: kind || "" })]);
  }

  function inertiaRows(inertia, kind) {
    if (!inertia) return [row(kind, "none", kind)];
    var rows = [
      row(kind + " mass", number(inertia.mass, "kg"), kind),
      row(kind + " moments", inertia.moments.map(function (m) { return number(m); }).join(", ") + " kg·m²", kind),
    ];
    if (inertia.box) rows.push(row(kind + " box", inertia.box.map(function (s) { return number(s); }).join(" × ") + " m", kind));
    if (inertia.problem) rows.push(row(kind + " box", inertia.problem, "problem"));
    if (kind === "geometry" && inertia.basis) rows.push(row("basis", inertia.basis, kind));
    return rows;
  }

  function findingItem(finding) {
    var where = finding.file
      ? finding.file + (finding.line ? ":" + finding.line : "") + (finding.column ? ":" + finding.column : "")
      : "";
    return element("li", {}, [
      element("span", { class: "code " + finding.severity, text: finding.code + " " }),
      element("span", { text: finding.message }),
      // what to do, as inertia-lint's `help:` line says it
      finding.help ? element("div", { class: "help", text: "help: " + finding.help }) : null,
      where ? element("div", { class: "where", text: where }) : null,
    ]);
  }

  function card(record, onClick) {
    var heading = element("h2", {}, [element("span", { text: record.name })]);
    if (record.worst) heading.appendChild(element("span", { class: "badge " + record.worst, text: record.worst }));
    var table = element("table", {}, [].concat(
      inertiaRows(record.declared, "declared"),
      inertiaRows(record.geometry, "geometry"),
      [row("implied density", number(record.implied_density, "kg/m³"))],
      record.shown === "collision" ? [row("drawn", "collision geometry (no visual)")] : []
    ));
    var findings = element("ul", { class: "findings" }, (record.findings || []).map(findingItem));
    var classes = "link" + (record.worst ? " worst-" + record.worst : "");
    var node = element("div", { class: classes, "data-link": record.name }, [heading, table, findings]);
    node.addEventListener("click", function () { onClick(record.name); });
    return node;
  }

  // the panel's content; returns each link's card by name, a Map (onClick(name) when one is
  // clicked)
  function fill(panel, scene, onClick) {
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
      var node = card(record, onClick);
      cards.set(record.name, node);
      panel.appendChild(node);
    });
    return cards;
  }

  return { element: element, legend: legend, fill: fill };
})();
