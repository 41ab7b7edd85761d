// Student pages, made better with JavaScript (they work without it):
// - a live preview of how each answer is read, debounced, from POST /preview;
// - verdicts that update themselves while an attempt is being graded (polling its status).
(function () {
  "use strict";
  var csrf = document.querySelector('meta[name="csrf-token"]').getAttribute("content");

  // ---- live preview -------------------------------------------------------------------------
  var form = document.querySelector("form[data-preview-url]");
  if (form) {
    var url = form.getAttribute("data-preview-url");
    var problem = form.getAttribute("data-problem");
    form.querySelectorAll("input[data-answer]").forEach(function (input) {
      var answer = input.getAttribute("data-answer");
      var box = document.getElementById("preview-" + answer);
      var timer = null, sequence = 0, shown = 0;
      function show(html, isError) {  // html comes from our own template, rendered by the server
        box.innerHTML = html;
        box.classList.toggle("error", isError);
      }
      function say(message, isError) {  // plain text, never parsed as HTML
        var span = document.createElement("span");
        span.className = "small" + (isError ? "" : " muted");
        span.textContent = message;
        box.replaceChildren(span);
        box.classList.toggle("error", isError);
      }
      function ask() {
        var mine = ++sequence;
        fetch(url, {
          method: "POST", credentials: "same-origin",
          headers: {"Content-Type": "application/json", "X-CSRF-Token": csrf},
          body: JSON.stringify({problem: problem, answer: answer, text: input.value})
        }).then(function (response) {
          return response.json().then(function (body) { return {ok: response.ok, body: body}; });
        }).then(function (reply) {
          if (mine < shown) return;  // an older request answered late: keep the newer preview
          shown = mine;
          if (!reply.ok) { say(reply.body.error || "Preview unavailable.", true); return; }
          var body = reply.body;
          show(body.html, !body.ok && !(body.error && body.error.code === "empty"));
        }).catch(function () {
          if (mine >= shown) say("Preview unavailable: reload the page (are you still signed in?).", false);
        });
      }
      input.addEventListener("input", function () {
        clearTimeout(timer);
        timer = setTimeout(ask, 250);
      });
      if (input.value && !box.querySelector(".reads, [role=alert]")) ask();
    });
  }

  // ---- verdicts of attempts being graded ------------------------------------------------------
  function poll(element, delay) {
    var url = element.getAttribute("data-poll");
    setTimeout(function () {
      fetch(url, {credentials: "same-origin", headers: {"Accept": "application/json"}})
        .then(function (response) { return response.json(); })
        .then(function (status) {
          document.querySelectorAll('[data-status-of="' + status.id + '"]').forEach(function (badge) {
            badge.textContent = status.label;
            badge.className = "badge " + status.css;
          });
          if (status.pending) { poll(element, Math.min(delay * 1.5, 5000)); return; }
          var holder = document.createElement("div");
          holder.innerHTML = status.html;
          var fresh = holder.firstElementChild;
          element.replaceWith(fresh);
        })
        .catch(function () { poll(element, Math.min(delay * 2, 10000)); });
    }, delay);
  }
  document.querySelectorAll("[data-poll]").forEach(function (element) { poll(element, 700); });
})();
