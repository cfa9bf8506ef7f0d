/* The page's first script, so that an error in three.js or in page.js is recorded too: every
 * uncaught error, unhandled rejection and console.error goes into #page-errors, which the
 * browser tests read (empty: a page without errors) and a reader sees. */
(function () {
  "use strict";
  var box = document.getElementById("page-errors");
  function record(text) {
    box.hidden = false;
    box.textContent += text + "\n";
  }
  window.onerror = function (message, source, line) {
    record("error: " + message + " (line " + line + ")");
  };
  window.addEventListener("unhandledrejection", function (event) {
    record("unhandled rejection: " + event.reason);
  });
  var original = console.error;
  console.error = function () {
    record("console.error: " + Array.prototype.map.call(arguments, String).join(" "));
    return original.apply(console, arguments);
  };
})();
