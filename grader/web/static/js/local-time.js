// Times are sent in UTC inside <time datetime="..." data-local>; show each in the reader's time zone,
// keeping the UTC text as its tooltip. Without script the UTC text stays, labelled "UTC".
(function () {
  "use strict";
  var format = new Intl.DateTimeFormat(undefined, { dateStyle: "medium", timeStyle: "short" });
  var zone = Intl.DateTimeFormat().resolvedOptions().timeZone || "";
  document.querySelectorAll("time[data-local]").forEach(function (node) {
    var moment = new Date(node.getAttribute("datetime"));
    if (isNaN(moment.getTime())) { return; }
    node.title = node.textContent;
    node.textContent = format.format(moment) + (zone ? " (" + zone.replace(/_/g, " ") + ")" : "");
  });
})();
