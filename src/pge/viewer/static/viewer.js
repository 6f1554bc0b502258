// pge viewer: plays a recording converted by pge.viewer.data (see that module for the layout).
// Vanilla JavaScript with no dependencies, so the page works offline and as one file.
(function () {
  "use strict";

  var EVENT_ROWS = 200; // events listed at most: older ones scroll out, the page stays quick
  var SPEEDS = [0.0625, 0.125, 0.25, 0.5, 1, 2, 4, 8, 16];

  var el = function (id) { return document.getElementById(id); };
  var canvas = el("pge-canvas"), ctx = canvas.getContext("2d");
  var seek = el("pge-seek"), playButton = el("pge-play"), speedSelect = el("pge-speed");
  var statusLine = el("pge-status"), eventList = el("pge-events");
  var params = new URLSearchParams(window.location.search);

  var data = null, times = null;
  var index = 0, playing = false, speed = 1, clock = 0, lastWall = 0;
  var eventStart = [];  // eventStart[k]: events listed before frame k (cumulative count)
  var allEvents = [];   // every event, in frame order: [frame, event]
  var listedFor = -1;   // the frame the event list was built for
  var cssWidth = 0, cssHeight = 0;

  function fail(message) {
    statusLine.textContent = "cannot show the recording: " + message;
    statusLine.className = "pge-status pge-error";
    window.pgeViewer.error = message;
  }

  function load() {
    var holder = el("pge-data");
    var text = holder.textContent.trim();
    if (text && text.charAt(0) === "{") {
      start(JSON.parse(text));
      return;
    }
    fetch(holder.getAttribute("data-src"), { cache: "no-store" })
      .then(function (r) { if (!r.ok) { throw new Error("HTTP " + r.status); } return r.json(); })
      .then(start)
      .catch(function (e) { fail(String(e.message || e)); });
  }

  function start(d) {
    data = d;
    times = d.times;
    var k;
    for (k = 0; k < d.frames.length; k++) {
      eventStart.push(allEvents.length);
      d.frames[k].e.forEach(function (e) { allEvents.push([k, e]); });
    }
    eventStart.push(allEvents.length);
    seek.max = String(times.length - 1);
    el("pge-title").textContent = d.title;
    document.title = d.title + " - pge viewer";
    var bodies = Object.keys(d.bodies).length;
    el("pge-info").textContent = d.format + " \u00b7 " + times.length + " frames \u00b7 " + bodies + " bodies \u00b7 " +
      fmt(times[0], 3) + " s to " + fmt(d.end_time, 3) + " s";
    el("pge-event-count").textContent = "(" + allEvents.length + ")";
    var s = Number(params.get("speed"));
    if (SPEEDS.indexOf(s) >= 0) { setSpeed(s); }
    resize();
    var first = Number(params.get("frame"));
    show(Number.isInteger(first) ? first : 0);
    window.pgeViewer.ready = true;
    if (params.get("autoplay") === "1") { play(); }
  }

  function fmt(x, digits) { return x === null ? "?" : Number(x).toFixed(digits); }

  // Canvas size: the world's aspect, as large as the stage allows (or ?size=N on the longer side),
  // backed by devicePixelRatio pixels per CSS pixel so shapes stay sharp.
  function resize() {
    if (!data) { return; }
    var b = data.bounds, w = b[2] - b[0], h = b[3] - b[1];
    var fixed = Number(params.get("size"));
    var boxW, boxH;
    if (fixed > 0) { boxW = boxH = fixed; } else {
      var stage = canvas.parentNode.getBoundingClientRect();
      boxW = Math.max(100, stage.width); boxH = Math.max(100, stage.height);
    }
    var k = Math.min(boxW / w, boxH / h);
    cssWidth = Math.max(1, Math.round(w * k)); cssHeight = Math.max(1, Math.round(h * k));
    var ratio = fixed > 0 ? 1 : (window.devicePixelRatio || 1);
    canvas.style.width = cssWidth + "px"; canvas.style.height = cssHeight + "px";
    canvas.width = Math.round(cssWidth * ratio); canvas.height = Math.round(cssHeight * ratio);
    draw();
  }

  function rgb(c) { var v = data.colours[c] || [255, 0, 255]; return "rgb(" + v[0] + "," + v[1] + "," + v[2] + ")"; }

  function draw() {
    if (!data) { return; }
    var b = data.bounds, f = data.frames[index];
    var sx = canvas.width / (b[2] - b[0]), sy = canvas.height / (b[3] - b[1]);
    ctx.fillStyle = rgb(data.background);
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    var c = f.c, k;
    for (k = 0; k < c.length; k += 4) {  // circles: x, y, r, colour
      ctx.fillStyle = rgb(c[k + 3]);
      ctx.beginPath();
      ctx.ellipse((c[k] - b[0]) * sx, (b[3] - c[k + 1]) * sy, c[k + 2] * sx, c[k + 2] * sy, 0, 0, 2 * Math.PI);
      ctx.fill();
    }
    f.p.forEach(function (p) {  // polygons: colour, x0, y0, x1, y1, ...
      ctx.fillStyle = rgb(p[0]);
      ctx.beginPath();
      for (var j = 1; j < p.length; j += 2) { ctx.lineTo((p[j] - b[0]) * sx, (b[3] - p[j + 1]) * sy); }
      ctx.closePath();
      ctx.fill();
    });
  }

  function label(id) {
    if (id < 0) { return "?"; }
    var body = data.bodies[String(id)];
    return body && body[1] ? body[1] : "#" + id;
  }

  function listEvents() {
    if (listedFor === index) { return; }
    listedFor = index;
    var end = eventStart[index + 1], begin = Math.max(0, end - EVENT_ROWS);
    var now = eventStart[index];
    var rows = document.createDocumentFragment();
    for (var k = begin; k < end; k++) {
      var e = allEvents[k][1], li = document.createElement("li");
      if (e[1] === "c") {
        li.textContent = fmt(e[0], 4) + "  " + label(e[2]) + " hit " + label(e[3]) + "  J " + fmt(e[6], 3);
      } else {
        li.textContent = fmt(e[0], 4) + "  timer " + e[2];
        li.className = "pge-timer";
      }
      if (k >= now) { li.className += " pge-now"; }
      rows.appendChild(li);
    }
    eventList.replaceChildren(rows);
    eventList.scrollTop = eventList.scrollHeight;
  }

  function status() {
    var last = times.length - 1;
    var mode = playing ? "playing" : (index === last ? "end" : "paused");
    statusLine.textContent = "t " + fmt(times[index], 4) + " s / " + fmt(data.end_time, 3) + " s   frame " + index +
      "/" + last + "   " + mode;
    playButton.textContent = playing ? "Pause" : "Play";
  }

  function show(k) {
    if (!data) { return; }
    index = Math.max(0, Math.min(times.length - 1, Math.round(Number(k)) || 0));
    clock = times[index];
    seek.value = String(index);
    draw();
    listEvents();
    status();
  }

  // The frame shown at simulated time t: the last one at or before it (binary search).
  function frameAt(t) {
    var lo = 0, hi = times.length - 1;
    if (t < times[0]) { return 0; }
    while (lo < hi) { var mid = (lo + hi + 1) >> 1; if (times[mid] <= t) { lo = mid; } else { hi = mid - 1; } }
    return lo;
  }

  function tick(now) {
    if (!playing) { return; }
    clock += (now - lastWall) / 1000 * speed;
    lastWall = now;
    var k = frameAt(clock);
    var end = Math.max(times[times.length - 1], data.end_time);
    if (k !== index) { var keep = clock; show(k); clock = keep; }
    if (clock >= end || times.length === 1) { pause(); return; }
    requestAnimationFrame(tick);
  }

  function play() {
    if (!data || playing) { return; }
    if (index === times.length - 1) { show(0); }  // at the end: play again from the start
    playing = true;
    lastWall = performance.now();
    status();
    requestAnimationFrame(tick);
  }

  function pause() { playing = false; if (data) { status(); } }

  function step(n) { pause(); show(index + n); }

  function setSpeed(s) {
    speed = Number(s);
    speedSelect.value = String(speed);
  }

  function changeSpeed(up) {
    var k = SPEEDS.indexOf(speed) + (up ? 1 : -1);
    if (k >= 0 && k < SPEEDS.length) { setSpeed(SPEEDS[k]); }
  }

  playButton.addEventListener("click", function () { if (playing) { pause(); } else { play(); } });
  el("pge-back").addEventListener("click", function () { step(-1); });
  el("pge-forward").addEventListener("click", function () { step(1); });
  el("pge-first").addEventListener("click", function () { pause(); show(0); });
  el("pge-last").addEventListener("click", function () { pause(); show(times.length - 1); });
  seek.addEventListener("input", function () { pause(); show(seek.value); });
  speedSelect.addEventListener("change", function () { setSpeed(speedSelect.value); });
  window.addEventListener("resize", resize);
  document.addEventListener("keydown", function (e) {
    if (!data || e.target === speedSelect) { return; }
    var keys = {
      " ": function () { if (playing) { pause(); } else { play(); } },
      ArrowRight: function () { step(1); }, ArrowLeft: function () { step(-1); },
      ArrowUp: function () { step(10); }, ArrowDown: function () { step(-10); },
      Home: function () { pause(); show(0); }, End: function () { pause(); show(times.length - 1); },
      "+": function () { changeSpeed(true); }, "=": function () { changeSpeed(true); },
      "-": function () { changeSpeed(false); }
    };
    if (keys[e.key]) { keys[e.key](); e.preventDefault(); }
  });

  // For scripts and tests: drive the viewer and read what it shows.
  window.pgeViewer = {
    ready: false, error: null,
    play: play, pause: pause, step: step, seek: show, setSpeed: setSpeed,
    state: function () {
      return { index: index, time: times ? times[index] : null, frames: times ? times.length : 0,
               playing: playing, speed: speed, events: eventList.children.length,
               canvas: [canvas.width, canvas.height] };
    }
  };
  load();
})();
