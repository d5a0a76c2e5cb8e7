// swarmvm inspect: displays what the page's JSON says (generator/inspector/page.py computed it all).
// User text reaches the page only through textContent, never as markup.
"use strict";
(function () {
  var D = JSON.parse(document.getElementById("data").textContent);
  var runs = D.runs, events = D.events, nSup = D.supervisors.length;
  var last = 0;
  runs.forEach(function (r) { last = Math.max(last, r.v.length - 1); });
  var view = { i: 0, robot: 0, timer: null };
  var $ = function (id) { return document.getElementById(id); };
  var firedHas = D.fired.map(function (set) {
    var has = {};
    set.forEach(function (e) { has[e] = true; });
    return has;
  });

  function at(run, i) { return Math.min(i, run.v.length - 1); }
  function vectorOf(run, i) { return run ? D.vectors[run.v[at(run, i)]] : D.vectors[0]; }
  function stepNumber(i) { return D.first - 1 + i; }
  function occurred(run, i, event) {       // did anything of interest happen in run at index i?
    if (i < 1 || i >= run.v.length) return false;
    if (event === "violation") return run.x[i] > run.x[i - 1];
    return event < 0 ? D.fired[run.f[i]].length > 0 : !!firedHas[run.f[i]][event];
  }
  // The transitions taken in step i of run (every supervisor's, input by input, then the chosen
  // event's): [supervisor, from, to, event], as page.py walked them.
  function movesOf(run, i) {
    if (!run || i < 1 || i >= run.v.length) return [];
    return D.moves[run.v[i - 1] + "," + run.f[i]] || [];
  }
  function el(tag, text, cls) {
    var e = document.createElement(tag);
    if (text !== undefined) e.textContent = text;
    if (cls) e.className = cls;
    return e;
  }
  function chip(event) {
    var ev = events[event];
    return el("span", "EV_" + ev[0], "ev " + (ev[1] === "c" ? "controllable" : "uncontrollable") +
      (ev[2] ? " public" : ""));
  }
  function chips(list, into) {
    if (!list.length) into.appendChild(el("span", "none", "none"));
    list.forEach(function (e) { into.appendChild(chip(e)); into.appendChild(document.createTextNode(" ")); });
  }

  // The drawings: per supervisor, its nodes by state and its edges (from, to, event name).
  var figures = [];
  document.querySelectorAll("figure.sup").forEach(function (fig) {
    var nodes = {}, edges = [], counts = {};
    fig.querySelectorAll("g.node").forEach(function (g) {
      var m = /^q(\d+)$/.exec(g.querySelector("title").textContent);
      if (!m) return;
      nodes[m[1]] = g;
      var label = g.querySelector("text");
      var count = label.cloneNode(false);       // an SVG text element, as Graphviz made it
      var ellipse = g.querySelector("ellipse");
      count.setAttribute("x", String(parseFloat(ellipse.getAttribute("cx")) + parseFloat(ellipse.getAttribute("rx"))));
      count.setAttribute("y", String(parseFloat(ellipse.getAttribute("cy")) + parseFloat(ellipse.getAttribute("ry")) + 4));
      count.setAttribute("text-anchor", "start");
      count.setAttribute("class", "count");
      g.appendChild(count);
      counts[m[1]] = count;
    });
    fig.querySelectorAll("g.edge").forEach(function (g) {
      var m = /^q(\d+)->q(\d+)$/.exec(g.querySelector("title").textContent);
      var label = g.querySelector("text");
      if (m) edges.push({ g: g, from: +m[1], to: +m[2], name: label ? label.textContent : "" });
    });
    figures.push({ fig: fig, nodes: nodes, edges: edges, counts: counts, where: fig.querySelector(".where") });
  });

  function drawGraphs() {
    var shown = D.compare ? [0, 1] : [view.robot];
    figures.forEach(function (f, s) {
      var counts = {};
      runs.forEach(function (r) { var q = vectorOf(r, view.i)[s]; counts[q] = (counts[q] || 0) + 1; });
      Object.keys(f.nodes).forEach(function (q) {
        var g = f.nodes[q];
        g.classList.toggle("occupied", !!counts[q]);
        g.classList.remove("cur", "cur-b");
        f.counts[q].textContent = runs.length > 1 && counts[q] ? "\u00d7" + counts[q] : "";
      });
      var here = [];
      shown.forEach(function (k, n) {
        var q = vectorOf(runs[k], view.i)[s];
        if (f.nodes[q]) f.nodes[q].classList.add(n ? "cur-b" : "cur");
        here.push(String(q));
      });
      f.where.textContent = runs.length ? "state " + here.join(" / ") : "initial state 0";
      var marks = {};                         // "from,to,event name" -> [run shown first?, second?]
      shown.forEach(function (k, n) {
        movesOf(runs[k], view.i).forEach(function (m) {
          if (m[0] !== s) return;
          var key = m[1] + "," + m[2] + "," + events[m[3]][0];
          (marks[key] = marks[key] || [false, false])[n] = true;
        });
      });
      f.edges.forEach(function (e) {
        var mark = marks[e.from + "," + e.to + "," + e.name] || [false, false];
        e.g.classList.toggle("fired", mark[0]);
        e.g.classList.toggle("fired-b", mark[1]);
      });
    });
  }

  function panel(k) {
    var run = runs[k], i = at(run, view.i), box = el("div", undefined, "panel");
    var fired = i > 0 && view.i < run.v.length ? D.fired[run.f[i]] : [];
    box.appendChild(el("h3", run.name + (view.i >= run.v.length ? " (ended)" : "")));
    var rows = [
      ["states", vectorOf(run, i).join(",")],
      ["inputs", fired.filter(function (e) { return events[e][1] === "u"; })],
      ["chosen", fired.filter(function (e) { return events[e][1] === "c"; })],
      ["enabled", D.enabled[run.v[i]]],
      ["violations", run.x[i] + (occurred(run, i, "violation") ? " (+" + (run.x[i] - run.x[i - 1]) + " here)" : "")]];
    var table = el("table");
    rows.forEach(function (row) {
      var tr = el("tr"), td = el("td");
      tr.appendChild(el("th", row[0]));
      if (typeof row[1] === "string") td.textContent = row[1]; else chips(row[1], td);
      td.className = row[0];
      tr.appendChild(td);
      table.appendChild(tr);
    });
    if (occurred(run, i, "violation")) box.classList.add("violated");
    box.appendChild(table);
    return box;
  }

  function line(run, i) {
    if (i === 0) return (D.first === 1 ? "reset " : "before ") + vectorOf(run, 0).join(",") + " " + run.x[0];
    var names = D.fired[run.f[i]].map(function (e) { return "EV_" + events[e][0]; });
    return stepNumber(i) + " " + (names.join(",") || "-") + " " + vectorOf(run, i).join(",") + " " + run.x[i];
  }

  function logSteps() {
    var run = runs[view.robot], event = +$("event").value, filter = $("filter").checked && event >= 0;
    var steps = [], i;
    var wanted = function (j) { return !filter || occurred(run, j, event); };
    for (i = view.i - 1; i >= 0 && steps.length < 8; i--) if (wanted(i)) steps.unshift(i);
    for (i = view.i; i < run.v.length && steps.length < 17; i++) if (wanted(i)) steps.push(i);
    return steps;
  }

  function drawLog() {
    var table = $("logTable");
    table.textContent = "";
    if (!runs.length) return;
    var head = el("tr");
    head.appendChild(el("th", "index"));
    (D.compare ? [0, 1] : [view.robot]).forEach(function (k) { head.appendChild(el("th", runs[k].name)); });
    table.appendChild(head);
    logSteps().forEach(function (i) {
      var tr = el("tr"), a = line(runs[D.compare ? 0 : view.robot], i);
      tr.appendChild(el("td", String(i)));
      tr.appendChild(el("td", a));
      if (D.compare) {
        var b = i < runs[1].v.length ? line(runs[1], i) : "(ended)";
        tr.appendChild(el("td", b));
        if (a !== b) tr.classList.add("differs");
      }
      if (i === view.i) tr.classList.add("here");
      tr.addEventListener("click", function () { go(i); });
      table.appendChild(tr);
    });
  }

  // The timeline: one lane per robot, a column per group of steps; red where a violation
  // happened, blue where the chosen event fired, grey where the VM chose an event.
  var canvas = $("timeline"), ctx = canvas.getContext("2d"), lane = 14, strip = null;
  function drawLanes() {
    canvas.height = Math.max(1, runs.length) * lane + 4;
    var width = canvas.width, event = +$("event").value;
    ctx.fillStyle = "#fff";
    ctx.fillRect(0, 0, width, canvas.height);
    runs.forEach(function (run, k) {
      var y = k * lane + 2;
      ctx.fillStyle = "#eceff1";
      ctx.fillRect(0, y, width * (run.v.length - 1) / Math.max(1, last), lane - 3);
      for (var i = 1; i < run.v.length; i++) {
        var colour = occurred(run, i, "violation") ? "#c62828" : event >= 0 && occurred(run, i, event) ? "#1565c0" :
          null;
        if (!colour) continue;
        ctx.fillStyle = colour;
        ctx.fillRect(Math.floor(width * (i - 0.5) / Math.max(1, last)), y, Math.max(1, width / Math.max(1, last)),
          lane - 3);
      }
    });
    strip = ctx.getImageData(0, 0, width, canvas.height);
  }
  function drawCursor() {
    if (!strip) return;
    ctx.putImageData(strip, 0, 0);
    var x = Math.round(canvas.width * view.i / Math.max(1, last));
    ctx.strokeStyle = "#ff8f00";
    ctx.lineWidth = 2;
    ctx.strokeRect(0, view.robot * lane + 1, canvas.width, lane - 1);
    ctx.fillStyle = "#000";
    ctx.fillRect(Math.min(x, canvas.width - 2), 0, 2, canvas.height);
  }

  function render() {
    $("slider").value = String(view.i);
    $("stepLabel").textContent = view.i === 0 ? (D.first === 1 ? "reset" : "before step " + D.first) :
      "step " + stepNumber(view.i) + " of " + stepNumber(last);
    document.body.dataset.step = String(stepNumber(view.i));
    document.body.dataset.robot = String(view.robot);
    drawGraphs();
    var panels = $("panels");
    panels.textContent = "";
    (D.compare ? [0, 1] : runs.length ? [view.robot] : []).forEach(function (k) { panels.appendChild(panel(k)); });
    if (!runs.length) panels.appendChild(el("p", "No trace given: the supervisors in their initial states."));
    drawLog();
    drawCursor();
    document.querySelectorAll("#laneNames span").forEach(function (s, k) {
      s.classList.toggle("selected", k === view.robot);
    });
  }

  function go(i) { view.i = Math.max(0, Math.min(last, i)); $("status").textContent = ""; render(); }
  function robot(k) { if (runs.length) { view.robot = (k + runs.length) % runs.length; render(); } }
  function seek(what, direction) {
    // The robot shown's next (direction 1) or previous (-1) step where what occurred; when it has
    // none, the nearest such step of another robot (the first in lane order at that step); when
    // no robot has one, the view stays and #status says so.
    var name = what === "violation" ? "violation" : what < 0 ? "event" : "EV_" + events[what][0];
    var which = (direction > 0 ? "next " : "previous ") + name, i, k, shown = runs[view.robot];
    if (!shown) return false;
    for (i = view.i + direction; i >= 1 && i <= last; i += direction) {
      if (occurred(shown, i, what)) { go(i); return true; }
    }
    for (i = view.i + direction; i >= 1 && i <= last; i += direction) {
      for (k = 0; k < runs.length; k++) {
        if (k !== view.robot && occurred(runs[k], i, what)) {
          view.robot = k;
          go(i);
          $("status").textContent = "no " + which + " in " + shown.name + ": " + runs[k].name + "'s shown";
          return true;
        }
      }
    }
    $("status").textContent = "no " + which + (runs.length > 1 ? " in any robot" : "");
    return false;
  }
  function play() {
    if (view.timer) { clearInterval(view.timer); view.timer = null; $("play").textContent = "play"; return; }
    if (view.i >= last) go(0);
    $("play").textContent = "pause";
    view.timer = setInterval(function () {
      if (view.i >= last) { play(); return; }
      go(view.i + 1);
    }, 1000 / +$("speed").value);
  }
  function speed(direction) {
    var select = $("speed");
    select.selectedIndex = Math.max(0, Math.min(select.options.length - 1, select.selectedIndex + direction));
    if (view.timer) { play(); play(); }
  }
  function difference() {      // the first difference among the steps kept (the summary says where the runs' is)
    if (D.differenceShown !== null) go(D.differenceShown - D.first + 1);
    else if (D.difference !== null) $("status").textContent = "no difference in the steps shown";
  }

  // The static parts: summary, event list, lanes' names, whole runs.
  var total = runs.reduce(function (n, r) { return n + r.steps; }, 0);
  var kept = runs.reduce(function (n, r) { return n + r.v.length - 1; }, 0);
  var summary = nSup + " supervisors, " + events.length + " events, " + runs.length + " trace" +
    (runs.length === 1 ? "" : "s") + "; steps " + (last ? D.first + " to " + stepNumber(last) : "none") + " shown";
  if (kept < total) {
    summary += " (" + kept + " of " + total + " robot-steps: a page keeps " + D.robotSteps +
      "; write another with --first-step for the rest)";
  }
  if (D.compare) {
    if (D.difference === null) summary += "; the two runs are identical";
    else {
      summary += "; the runs first differ at step " + D.difference + " (" + D.differences + " of " +
        Math.max(runs[0].steps, runs[1].steps) + " steps differ)";
      if (D.differenceShown === null) summary += ", none of the steps shown";
      else if (D.differenceShown !== D.difference) summary += ", first in the steps shown at " + D.differenceShown;
      if (D.difference < D.first || D.difference > stepNumber(last)) {
        summary += " (--first-step " + D.difference + " shows step " + D.difference + ")";
      }
    }
    $("difference").hidden = false;
  }
  $("summary").textContent = summary;
  events.forEach(function (ev, e) {
    var option = el("option", "EV_" + ev[0] + (ev[1] === "c" ? " (controllable)" : " (uncontrollable)"));
    option.value = String(e);
    $("event").appendChild(option);
  });
  runs.forEach(function (run, k) {
    var s = el("span", run.name, "lane");
    s.addEventListener("click", function () { robot(k); });
    $("laneNames").appendChild(s);
  });
  var runTable = $("runTable");
  var head = el("tr");
  ["trace", "steps", "last states", "violations", "events fired most"].forEach(function (h) {
    head.appendChild(el("th", h));
  });
  runTable.appendChild(head);
  runs.forEach(function (run) {
    var tr = el("tr"), top = run.counts.map(function (c, e) { return [c, e]; }).filter(function (p) { return p[0]; });
    top.sort(function (a, b) { return b[0] - a[0] || a[1] - b[1]; });
    [run.name, String(run.steps), D.vectors[run.last].join(","), String(run.lastViolations),
      top.slice(0, 5).map(function (p) { return "EV_" + events[p[1]][0] + " \u00d7" + p[0]; }).join(", ")]
      .forEach(function (text) { tr.appendChild(el("td", text)); });
    runTable.appendChild(tr);
  });

  $("slider").max = String(last);
  $("slider").addEventListener("input", function () { go(+$("slider").value); });
  $("begin").addEventListener("click", function () { go(0); });
  $("back").addEventListener("click", function () { go(view.i - 1); });
  $("forward").addEventListener("click", function () { go(view.i + 1); });
  $("end").addEventListener("click", function () { go(last); });
  $("play").addEventListener("click", play);
  $("nextEvent").addEventListener("click", function () { seek(+$("event").value, 1); });
  $("nextViolation").addEventListener("click", function () { seek("violation", 1); });
  $("difference").addEventListener("click", difference);
  // A choice made, the keys go back to the page's shortcuts.
  $("event").addEventListener("change", function () { $("event").blur(); drawLanes(); render(); });
  $("filter").addEventListener("change", render);
  $("speed").addEventListener("change", function () { $("speed").blur(); if (view.timer) { play(); play(); } });
  canvas.addEventListener("click", function (e) {
    var box = canvas.getBoundingClientRect();
    var k = Math.floor((e.clientY - box.top) * canvas.height / box.height / lane);
    if (k >= 0 && k < runs.length) view.robot = k;
    go(Math.round((e.clientX - box.left) * last / box.width));
  });
  var keys = {
    ArrowRight: function (e) { go(view.i + (e.shiftKey ? 10 : 1)); },
    ArrowLeft: function (e) { go(view.i - (e.shiftKey ? 10 : 1)); },
    ArrowUp: function () { robot(view.robot - 1); },
    ArrowDown: function () { robot(view.robot + 1); },
    Home: function () { go(0); },
    End: function () { go(last); },
    " ": play,
    "+": function () { speed(1); },
    "-": function () { speed(-1); },
    e: function () { seek(+$("event").value, 1); },
    E: function () { seek(+$("event").value, -1); },
    v: function () { seek("violation", 1); },
    V: function () { seek("violation", -1); },
    d: difference
  };
  document.addEventListener("keydown", function (e) {
    var action = keys[e.key];
    if (!action || e.ctrlKey || e.altKey || e.metaKey || e.target.tagName === "SELECT") return;
    e.preventDefault();
    action(e);
  });
  drawLanes();
  render();
  document.body.dataset.ready = "1";
})();
