// swarmvm inspect: displays what the page's JSON says (generator/inspector/page.py computed the
// replay); the simulator fires events on the supervisors' tables the JSON carries, as the VM does.
// User text reaches the page only through textContent, never as markup.
"use strict";
(function () {
  var D = JSON.parse(document.getElementById("data").textContent);
  var runs = D.runs, events = D.events, nSup = D.supervisors.length;
  var last = 0;
  runs.forEach(function (r) { last = Math.max(last, r.kept); });
  var view = { i: 0, robot: 0, timer: null };
  var $ = function (id) { return document.getElementById(id); };
  var firedHas = D.fired.map(function (set) {
    var has = {};
    set.forEach(function (e) { has[e] = true; });
    return has;
  });

  // The runs' steps, packed (swarmvm.inspector.encoding): a run is one code a step, a row of
  // D.table ([vector, fired, violations added]), in base64. A run's codes are decoded into a
  // typed array when the run is first needed (its lane drawn, a step of it shown), its violation
  // counters summed when first asked; a step's states and events are looked up in the table.
  // Index 0 of a run is the state before its first step kept; index i, step D.first + i - 1.
  var rowVector = Int32Array.from(D.table, function (row) { return row[0]; });
  var rowFired = Int32Array.from(D.table, function (row) { return row[1]; });
  var rowAdded = Int32Array.from(D.table, function (row) { return row[2]; });
  function codesOf(run) {
    if (!run.decoded) {
      var text = atob(run.codes), bytes = new Uint8Array(text.length);
      for (var n = 0; n < text.length; n++) bytes[n] = text.charCodeAt(n);
      run.decoded = D.codeBytes === 2 ? new Uint16Array(bytes.buffer) : new Uint32Array(bytes.buffer);
    }
    return run.decoded;
  }
  function vectorId(run, i) { return i ? rowVector[codesOf(run)[i - 1]] : run.start; }
  function firedId(run, i) { return i ? rowFired[codesOf(run)[i - 1]] : 0; }
  function violationsAt(run, i) {
    if (!run.counters) {
      var codes = codesOf(run), x = new Float64Array(codes.length + 1);
      x[0] = run.startViolations;
      for (var n = 0; n < codes.length; n++) x[n + 1] = x[n] + rowAdded[codes[n]];
      run.counters = x;
    }
    return run.counters[i];
  }

  function at(run, i) { return Math.min(i, run.kept); }
  function vectorOf(run, i) { return run ? D.vectors[vectorId(run, at(run, i))] : D.vectors[0]; }
  function stepNumber(i) { return D.first - 1 + i; }
  function occurred(run, i, event) {       // did anything of interest happen in run at index i?
    if (i < 1 || i > run.kept) return false;
    if (event === "violation") return rowAdded[codesOf(run)[i - 1]] > 0;
    var fired = firedId(run, i);
    return event < 0 ? D.fired[fired].length > 0 : !!firedHas[fired][event];
  }
  // The transitions taken in step i of run (every supervisor's, input by input, then the chosen
  // event's): [supervisor, from, to, event], the step's events fired again from the states
  // before it, as the simulator fires them (fireOn).
  function movesOf(run, i) {
    if (!run || i < 1 || i > run.kept) return [];
    var states = vectorOf(run, i - 1), moves = [];
    D.fired[firedId(run, i)].forEach(function (e) {
      var result = fireOn(states, e);
      moves = moves.concat(result.moves);
      states = result.states;
    });
    return moves;
  }
  // The supervisors' tables (page.py: D.alphabets, D.tables), for the simulator and for the
  // refusals at a violation: firing an event from any vector, as docs/semantics.md says.
  var holds = D.alphabets.map(function (alphabet) {
    var has = {};
    alphabet.forEach(function (e) { has[e] = true; });
    return has;
  });
  function target(s, q, event) {          // supervisor s's state after event from q, or -1
    var row = D.tables[s][q];
    for (var n = 0; n < row.length; n++) if (row[n][0] === event) return row[n][1];
    return -1;
  }
  function enabledAt(states, kind) {      // events of kind "c" or "u" every holder has a transition on
    var list = [];
    events.forEach(function (ev, e) {
      if (ev[1] !== kind) return;
      for (var s = 0; s < nSup; s++) if (holds[s][e] && target(s, states[s], e) < 0) return;
      list.push(e);
    });
    return list;
  }
  // Fire event from states: the states after, the moves [supervisor, from, to, event] and the
  // supervisors that refused it (a violation: they keep their state).
  function fireOn(states, event) {
    var after = states.slice(), moves = [], refused = [];
    for (var s = 0; s < nSup; s++) {
      if (!holds[s][event]) continue;
      var to = target(s, states[s], event);
      if (to < 0) refused.push(s); else { moves.push([s, states[s], to, event]); after[s] = to; }
    }
    return { states: after, moves: moves, refused: refused };
  }
  // Input order (docs/semantics.md, step 1): the public uncontrollable events, then the private
  // ones, each in event order; inputRank[e] is e's place in it.
  var inputRank = events.map(function () { return -1; }), ranked = 0;
  [1, 0].forEach(function (pub) {
    events.forEach(function (ev, e) { if (ev[1] === "u" && ev[2] === pub) inputRank[e] = ranked++; });
  });

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
    var nodes = {}, edges = [], counts = {}, start = [];    // start: the initial state's dot and arrow
    fig.querySelectorAll("g.node").forEach(function (g) {
      var m = /^q(\d+)$/.exec(g.querySelector("title").textContent);
      if (!m) { start.push(g); return; }
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
      else start.push(g);
    });
    var svg = fig.querySelector("svg"), f = { fig: fig, nodes: nodes, edges: edges, counts: counts,
      where: fig.querySelector(".where"), svg: svg, start: start, scale: null, framed: "",
      whole: [svg.getAttribute("viewBox"), svg.getAttribute("width"), svg.getAttribute("height")],
      font: parseFloat((svg.querySelector("text") || svg).getAttribute("font-size")) || 14, followed: "",
      caption: fig.querySelector("figcaption") };
    readable(f);
    var caption = f.caption;
    [["\u2212", "zoom out", 1 / 1.5], ["+", "zoom in (or Ctrl+wheel; drag to pan)", 1.5],
      ["fit", "fit the width (never below readable labels: a wider drawing pans)", 0]]
      .forEach(function (b) {
        var button = el("button", b[0], "zoomSup");
        button.title = b[1];
        button.addEventListener("click", function () { zoomFigure(f, b[2]); });
        caption.appendChild(button);
      });
    fig.addEventListener("wheel", function (e) {
      if (!e.ctrlKey) return;
      e.preventDefault();
      zoomFigure(f, e.deltaY > 0 ? 1 / 1.5 : 1.5);
    }, { passive: false });
    fig.addEventListener("mousedown", function (e) {
      if (e.target.tagName === "BUTTON") return;
      var x = e.clientX, y = e.clientY, left = fig.scrollLeft, top = fig.scrollTop;
      function move(m) { fig.scrollLeft = left - (m.clientX - x); fig.scrollTop = top - (m.clientY - y); }
      function up() { window.removeEventListener("mousemove", move); window.removeEventListener("mouseup", up); }
      window.addEventListener("mousemove", move);
      window.addEventListener("mouseup", up);
      e.preventDefault();
    });
    figures.push(f);
  });

  // A drawing's zoom: f.scale screen pixels per point of the drawing, null to fit the figure's
  // width; factor 0 fits, any other multiplies the scale shown.
  function zoomFigure(f, factor) {
    var points = parseFloat(f.svg.getAttribute("width"));
    if (!factor) f.scale = null;
    else f.scale = (f.scale || f.svg.getBoundingClientRect().width / points) * factor;
    f.svg.style.maxWidth = f.scale ? "none" : "";
    f.svg.style.width = f.scale ? Math.round(points * f.scale) + "px" : "";
    readable(f);
  }
  // Fitted (f.scale null), a drawing is never narrower than its labels can be read at 11
  // pixels: one wider than its box (a phone's width, a large supervisor) keeps that scale and
  // pans in its box instead of shrinking to a third. f.font: the labels' size in the drawing's
  // units (Graphviz' points, the viewBox's).
  function readable(f) {
    var pixels = 11;
    f.svg.style.minWidth = f.scale ? "" : (f.svg.viewBox.baseVal.width * pixels / f.font).toFixed(1) + "px";
  }
  // A drawing larger than its box: when the state highlighted changes and is out of the box's
  // view, the box scrolls to put it in the middle (the user's own panning is left alone).
  function keepInView(f) {
    var g = f.svg.querySelector("g.node.cur"), fig = f.fig, key = g ? g.querySelector("title").textContent : "";
    if (key === f.followed) return;
    f.followed = key;
    if (!g || (fig.scrollWidth <= fig.clientWidth && fig.scrollHeight <= fig.clientHeight)) return;
    // The state's circle (not its count) in the box's client area, under the caption that stays on top.
    var b = g.querySelector("ellipse").getBoundingClientRect(), r = fig.getBoundingClientRect();
    var left = b.left - r.left - fig.clientLeft, top = b.top - r.top - fig.clientTop, above = f.caption.offsetHeight;
    if (left >= 0 && left + b.width <= fig.clientWidth && top >= above && top + b.height <= fig.clientHeight) return;
    fig.scrollLeft += left + b.width / 2 - fig.clientWidth / 2;
    fig.scrollTop += top + b.height / 2 - (above + fig.clientHeight) / 2;
  }
  // The neighbourhood of the current states to a depth (the #depth list; -1: every state): the
  // states within that many transitions of one highlighted, either way, with the transitions
  // between them; the others hidden, and the drawing framed on what stays (Graphviz' layout
  // of the whole supervisor is kept, so a state stays where it was).
  function neighbourhood(f, from, depth) {
    var near = {}, frontier = from.slice(), n, k;
    from.forEach(function (q) { near[q] = true; });
    for (n = 0; n < depth; n++) {
      var next = [];
      for (k = 0; k < f.edges.length; k++) {
        var e = f.edges[k], a = frontier.indexOf(e.from) >= 0, b = frontier.indexOf(e.to) >= 0;
        if (a && !near[e.to]) { near[e.to] = true; next.push(e.to); }
        if (b && !near[e.from]) { near[e.from] = true; next.push(e.from); }
      }
      frontier = next;
    }
    var key = depth < 0 ? "" : Object.keys(near).sort().join(",");
    if (key === f.framed) return;
    f.framed = key;
    Object.keys(f.nodes).forEach(function (q) { f.nodes[q].style.display = depth < 0 || near[q] ? "" : "none"; });
    f.edges.forEach(function (e) { e.g.style.display = depth < 0 || near[e.from] && near[e.to] ? "" : "none"; });
    f.start.forEach(function (g) { g.style.display = depth < 0 || near[0] ? "" : "none"; });
    f.svg.setAttribute("viewBox", f.whole[0]);
    f.svg.setAttribute("width", f.whole[1]);
    f.svg.setAttribute("height", f.whole[2]);
    if (depth >= 0) frame(f, near);
    zoomFigure(f, f.scale ? 1 : 0);
  }
  function frame(f, near) {               // the viewBox around the states kept, their edges and labels
    var box = f.svg.viewBox.baseVal, r = f.svg.getBoundingClientRect();
    if (!r.width || !r.height) return;
    var sx = box.width / r.width, sy = box.height / r.height, x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
    var parts = Object.keys(near).map(function (q) { return f.nodes[q]; }).concat(f.edges.filter(function (e) {
      return near[e.from] && near[e.to]; }).map(function (e) { return e.g; }));
    parts.forEach(function (g) {
      if (!g) return;
      var b = g.getBoundingClientRect();
      x0 = Math.min(x0, box.x + (b.left - r.left) * sx);
      y0 = Math.min(y0, box.y + (b.top - r.top) * sy);
      x1 = Math.max(x1, box.x + (b.right - r.left) * sx);
      y1 = Math.max(y1, box.y + (b.bottom - r.top) * sy);
    });
    if (!(x1 > x0)) return;
    x0 -= 8; y0 -= 8; x1 += 8; y1 += 8;
    f.svg.setAttribute("viewBox", [x0, y0, x1 - x0, y1 - y0].map(function (v) { return v.toFixed(2); }).join(" "));
    f.svg.setAttribute("width", (x1 - x0).toFixed(2) + "pt");
    f.svg.setAttribute("height", (y1 - y0).toFixed(2) + "pt");
  }

  // What the drawings show of robot k: its trace's states and moves at the step shown, or, for
  // the robot the simulator started from, the simulator's.
  function statesShown(k) { return sim && k === sim.robot ? sim.now.states : vectorOf(runs[k], view.i); }
  function movesShown(k) { return sim && k === sim.robot ? sim.now.moves : movesOf(runs[k], view.i); }

  function drawGraphs() {
    var shown = D.compare ? [0, 1] : [view.robot];
    figures.forEach(function (f, s) {
      var counts = {};
      runs.forEach(function (r, k) { var q = statesShown(k)[s]; counts[q] = (counts[q] || 0) + 1; });
      Object.keys(f.nodes).forEach(function (q) {
        var g = f.nodes[q];
        g.classList.toggle("occupied", !!counts[q]);
        g.classList.remove("cur", "cur-b");
        f.counts[q].textContent = runs.length > 1 && counts[q] ? "\u00d7" + counts[q] : "";
      });
      var here = [];
      shown.forEach(function (k, n) {
        var q = statesShown(k)[s];
        if (f.nodes[q]) f.nodes[q].classList.add(n ? "cur-b" : "cur");
        here.push(String(q));
      });
      f.where.textContent = runs.length ? "state " + here.join(" / ") : "state " + statesShown(0)[s];
      var marks = {};                         // "from,to,event name" -> [run shown first?, second?]
      shown.forEach(function (k, n) {
        movesShown(k).forEach(function (m) {
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
      neighbourhood(f, here.map(Number), +$("depth").value);
    });
    figures.forEach(keepInView);            // after every drawing changed: one layout for all
  }

  function panel(k) {
    var run = runs[k], i = at(run, view.i), box = el("div", undefined, "panel");
    var fired = i > 0 && view.i <= run.kept ? D.fired[firedId(run, i)] : [];
    box.appendChild(el("h3", run.name + (view.i > run.kept ? " (ended)" : "")));
    var rows = [
      ["states", vectorOf(run, i).join(",")],
      ["inputs", fired.filter(function (e) { return events[e][1] === "u"; })],
      ["chosen", fired.filter(function (e) { return events[e][1] === "c"; })],
      ["enabled", D.enabled[vectorId(run, i)]],
      ["violations", violationsAt(run, i) + (occurred(run, i, "violation") ? " (+" +
        (violationsAt(run, i) - violationsAt(run, i - 1)) + " here)" : "")]];
    if (occurred(run, i, "violation")) rows.push(["refused", refusals(vectorOf(run, i - 1), fired)]);
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

  // At a violation, which supervisor refused which input: the step's events fired again from
  // the states before it, in firing order ("EV_x by supervisor 2 in q3").
  function refusals(before, fired) {
    var states = before, said = [];
    fired.forEach(function (e) {
      var result = fireOn(states, e);
      result.refused.forEach(function (s) {
        said.push("EV_" + events[e][0] + " by supervisor " + s + " in q" + states[s]);
      });
      states = result.states;
    });
    return said.join("; ");
  }

  function line(run, i) {
    if (i === 0) return (D.first === 1 ? "reset " : "before ") + vectorOf(run, 0).join(",") + " " + violationsAt(run, 0);
    var names = D.fired[firedId(run, i)].map(function (e) { return "EV_" + events[e][0]; });
    return stepNumber(i) + " " + (names.join(",") || "-") + " " + vectorOf(run, i).join(",") + " " + violationsAt(run, i);
  }

  function logSteps() {
    var run = runs[view.robot], event = +$("event").value, filter = $("filter").checked && event >= 0;
    var steps = [], i;
    var wanted = function (j) { return !filter || occurred(run, j, event); };
    for (i = view.i - 1; i >= 0 && steps.length < 8; i--) if (wanted(i)) steps.unshift(i);
    for (i = view.i; i <= run.kept && steps.length < 17; i++) if (wanted(i)) steps.push(i);
    return steps;
  }

  // A trace line as a cell that may wrap after each comma (a <wbr>, no text of its own), so that
  // a narrow column (a phone's, two runs side by side) breaks a list of events between two.
  function lineCell(text) {
    var td = el("td");
    text.split(",").forEach(function (part, n) {
      if (n) { td.appendChild(document.createTextNode(",")); td.appendChild(el("wbr")); }
      td.appendChild(document.createTextNode(part));
    });
    return td;
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
      tr.appendChild(lineCell(a));
      if (D.compare) {
        var b = i <= runs[1].kept ? line(runs[1], i) : "(ended)";
        tr.appendChild(lineCell(b));
        if (a !== b) tr.classList.add("differs");
      }
      if (i === view.i) tr.classList.add("here");
      tr.addEventListener("click", function () { go(i); });
      table.appendChild(tr);
    });
  }

  // The simulator (docs/inspect.md, "Simulator"): from the states shown, fire any enabled event
  // as a VM step takes them (docs/semantics.md): inputs (uncontrollable events) in input order,
  // each once, then one controllable event, which ends the step. The VM's own choice for the
  // seed and the policy is marked and is what "end step" fires, so that the path, saved as an
  // event script, replays under `swarmvm trace` to the same states. sim.now is replaced, never
  // changed, by each event: undo pops the previous one.
  var sim = null;
  function draw(x) {                      // xorshift32 (docs/semantics.md) on a 32-bit unsigned state
    x = (x ^ (x << 13)) >>> 0;
    x = (x ^ (x >>> 17)) >>> 0;
    return (x ^ (x << 5)) >>> 0;
  }
  function seedOf() {
    var seed = Math.max(0, Math.min(4294967295, Math.floor(+$("simSeed").value) || 0));
    return seed === 0 ? 0x9E3779B9 : seed;
  }
  // The VM's choice among the controllable events enabled (in event order), and the generator
  // after it: "first" never draws, "uniform" draws when there are two or more.
  function choice(enabled, rng) {
    if (!enabled.length) return { event: -1, rng: rng };
    if ($("simPolicy").value === "first" || enabled.length === 1) return { event: enabled[0], rng: rng };
    var r = draw(rng);
    return { event: enabled[((r >>> 16) * enabled.length) >>> 16], rng: r };
  }
  function names(list, sep) { return list.map(function (e) { return "EV_" + events[e][0]; }).join(sep); }
  function inputsOf(fired) { return fired.filter(function (e) { return events[e][1] === "u"; }); }

  function startSim() {
    var run = runs[view.robot], i = run ? at(run, view.i) : 0, rng = seedOf(), rows = [];
    var known = !run || D.first === 1;    // the script needs every step from 1: the page's window must start there
    if (run && known) {
      // The trace's steps up to i: their inputs are the script's first rows, and the generator
      // drew once in each whose choice had two or more candidates.
      for (var j = 1; j <= i; j++) {
        var states = vectorOf(run, j - 1), fired = D.fired[firedId(run, j)], chose = false;
        for (var n = 0; n < fired.length; n++) {
          if (events[fired[n]][1] === "u") states = fireOn(states, fired[n]).states; else chose = true;
        }
        if (chose) rng = choice(enabledAt(states, "c"), rng).rng;
        rows.push(inputsOf(fired));
      }
    }
    var first = { states: vectorOf(run, i).slice(), x: run ? violationsAt(run, i) : 0, step: run ? stepNumber(i) : 0, rng: rng,
      fired: [], moves: [], rows: rows, lines: [], offVM: [] };
    sim = { robot: run ? view.robot : 0, known: known, first: first, now: first, history: [],
      from: run ? (i ? "step " + stepNumber(i) : D.first === 1 ? "the reset" : "before step " + D.first) + " of " +
        run.name : "the initial states" };
  }
  function leaveSim() {
    if (!sim) return;
    sim = null;
    $("simStatus").textContent = "simulation left: fire an event to start again from the step shown";
  }
  function vmChoice() { return choice(enabledAt(sim.now.states, "c"), sim.now.rng); }
  // Inputs still possible in the step begun: enabled, and after the last one fired in input order.
  function inputPossible(e) {
    var fired = inputsOf(sim ? sim.now.fired : []);
    return !fired.length || inputRank[e] > inputRank[fired[fired.length - 1]];
  }
  function ended(next) {                   // next, with the step begun ended (its line and row added)
    next.step += 1;
    next.lines = next.lines.concat([next.step + " " + (names(next.fired, ",") || "-") + " " +
      next.states.join(",") + " " + next.x]);
    next.rows = next.rows.concat([inputsOf(next.fired)]);
    next.fired = [];
    return next;
  }
  function simFire(event) {
    if (!sim) startSim();
    var now = sim.now, result = fireOn(now.states, event);
    var next = { states: result.states, x: now.x + result.refused.length, step: now.step, rng: now.rng,
      fired: now.fired.concat([event]), moves: (now.fired.length ? now.moves : []).concat(result.moves),
      rows: now.rows, lines: now.lines, offVM: now.offVM };
    if (events[event][1] === "c") {
      var vm = vmChoice();
      next.rng = vm.rng;
      if (vm.event !== event) next.offVM = now.offVM.concat([now.step + 1]);
      next = ended(next);
    }
    sim.history.push(now);
    sim.now = next;
    $("simStatus").textContent = "";
    render();
  }
  function simStep() {                     // end the step: the VM's choice, or none when none is enabled
    if (!sim) startSim();
    var vm = vmChoice();
    if (vm.event >= 0) { simFire(vm.event); return; }
    var now = sim.now, next = Object.assign({}, now);
    next.moves = now.fired.length ? now.moves : [];
    sim.history.push(now);
    sim.now = ended(next);
    render();
  }
  function simUndo() {
    if (sim && sim.history.length) { sim.now = sim.history.pop(); render(); }
  }
  function simReset() {
    if (sim) { sim.now = sim.first; sim.history = []; render(); }
  }
  function scriptText() {
    var lines = ["# swarmvm event script: one step per line, the uncontrollable events that occur",
      "# replay: swarmvm trace " + D.source.replace(/[\x00-\x1f\x7f]/g, "?") + " --script FILE --seed " +
      $("simSeed").value + " --policy " + $("simPolicy").value];
    sim.now.rows.forEach(function (row) {
      lines.push(names(row.slice().sort(function (a, b) { return a - b; }), " ") || "-");
    });
    return lines.join("\n") + "\n";
  }
  function simSave() {
    if (!sim) startSim();
    if (!sim.known) {
      $("simStatus").textContent = "not saved: this page keeps the trace from step " + D.first +
        " on, and a script starts at step 1";
      return;
    }
    var link = el("a");
    link.href = URL.createObjectURL(new Blob([scriptText()], { type: "text/plain" }));
    link.download = D.title.replace(/[\x00-\x1f\x7f\/\\:*?"<>|]/g, "_") + ".script";
    document.body.appendChild(link);
    link.click();
    link.remove();
    $("simStatus").textContent = "saved " + link.download + " (" + sim.now.rows.length + " steps" +
      (sim.now.fired.length ? "; the step begun is not in it" : "") + ")" + (sim.now.offVM.length ?
      "; steps " + sim.now.offVM.join(", ") + " fired another event than the VM's choice: `swarmvm trace` " +
      "chooses otherwise there" : ": `swarmvm trace` replays it to these states");
    render();
  }

  var simDrawn = "";                       // what drawSim drew last: a step of the replay redraws it only when it differs
  function drawSim() {
    var states = sim ? sim.now.states : statesShown(view.robot), vm = sim ? vmChoice().event : -1;
    var begun = sim ? sim.now.fired : [];
    var drawn = sim ? "" : view.robot + "|" + states.join(",");
    if (drawn && drawn === simDrawn) return;
    simDrawn = drawn;
    $("simFrom").textContent = sim ? "From " + sim.from + "; step " + sim.now.step + (begun.length ? ", step " +
      (sim.now.step + 1) + " begun (" + names(begun, ", ") + ")" : "") + ": states " + states.join(",") +
      ", violations " + sim.now.x + "." : "Fire an event to simulate from " + (runs.length ?
      "the step shown of " + runs[view.robot].name : "the initial states") + ".";
    var box = $("simEvents");
    box.textContent = "";
    [["inputs", enabledAt(states, "u")], ["controllable", enabledAt(states, "c")]].forEach(function (group) {
      var row = el("div", undefined, "simGroup");
      row.appendChild(el("span", group[0] + " enabled: ", "simKind"));
      if (!group[1].length) row.appendChild(el("span", "none", "none"));
      group[1].forEach(function (e) {
        var look = chip(e), open = events[e][1] === "c" || inputPossible(e);
        var button = el("button", look.textContent + (e === vm ? " (VM's choice)" : ""), look.className +
          (e === vm ? " vm" : ""));
        button.value = String(e);
        button.disabled = !open;
        button.title = open ? (events[e][1] === "c" ? "fire it: it ends the step" : "fire it as an input of the step") :
          "comes before " + names(inputsOf(begun).slice(-1), "") + " in input order: end the step first";
        button.addEventListener("click", function () { simFire(e); });
        row.appendChild(button);
      });
      box.appendChild(row);
    });
    $("simUndo").disabled = !sim || !sim.history.length;
    $("simReset").disabled = !sim || !sim.history.length;
    var log = $("simLog");
    log.textContent = "";
    (sim ? sim.now.lines : []).forEach(function (text) {
      var tr = el("tr"), td = el("td", text);
      if (sim.now.offVM.indexOf(+text.split(" ")[0]) >= 0) {
        tr.className = "offvm";
        tr.title = "another event than the VM's choice";
      }
      tr.appendChild(td);
      log.appendChild(tr);
    });
    log.scrollTop = log.scrollHeight;      // the last step in view
    $("simScript").textContent = sim ? scriptText() : "";
  }

  // The timeline: one lane per robot (and, comparing, a lane of the steps where the two runs'
  // lines differ), each pixel column one step or a group of steps of the range shown (zoom and
  // pan): red where a violation happened, green where the search matches, blue where the chosen
  // event fired, grey where any event fired (in that order when a column holds several).
  var canvas = $("timeline"), ctx = canvas.getContext("2d"), lane = 14, strip = null;
  var range = { from: 0, span: Math.max(1, last) };   // the indices shown: from .. from + span
  var found = null;                                   // the search: { name, test(run, i) }
  var COLOURS = [null, "#90a4ae", "#1565c0", "#2e7d32", "#c62828", "#ad1457"];
  function lineDiffers(i) {
    var a = runs[0], b = runs[1];
    if (i > a.kept || i > b.kept) return true;
    return vectorId(a, i) !== vectorId(b, i) || firedId(a, i) !== firedId(b, i) || violationsAt(a, i) !== violationsAt(b, i);
  }
  var differs = [];                                   // comparing: per index, do the two lines differ?
  for (var d = 0; D.compare && d <= last; d++) differs.push(d > 0 && lineDiffers(d));
  function xOf(i) { return (i - range.from) * canvas.width / range.span; }
  function indexAt(fraction) { return Math.round(range.from + fraction * range.span); }
  function priority(run, i, event) {
    if (occurred(run, i, "violation")) return 4;
    if (found && found.test(run, i)) return 3;
    if (event >= 0) return occurred(run, i, event) ? 2 : 0;
    return occurred(run, i, -1) ? 1 : 0;
  }
  function paintLane(y, length, colourOf) {  // one lane: the colour of the highest priority per pixel
    var width = canvas.width, best = new Uint8Array(width), i, p;
    ctx.fillStyle = "#eceff1";
    ctx.fillRect(Math.max(0, xOf(0)), y, Math.max(0, Math.min(width, xOf(length - 1)) - Math.max(0, xOf(0))), lane - 3);
    var low = Math.max(1, Math.floor(range.from)), high = Math.min(length - 1, Math.ceil(range.from + range.span));
    for (i = low; i <= high; i++) {
      var level = colourOf(i);
      if (!level) continue;
      var x0 = Math.max(0, Math.floor(xOf(i - 0.5))), x1 = Math.min(width, Math.max(x0 + 1, Math.floor(xOf(i + 0.5))));
      for (p = x0; p < x1; p++) if (level > best[p]) best[p] = level;
    }
    for (p = 0; p < width; p++) {
      if (!best[p]) continue;
      var q = p;
      while (q + 1 < width && best[q + 1] === best[p]) q++;
      ctx.fillStyle = COLOURS[best[p]];
      ctx.fillRect(p, y, q - p + 1, lane - 3);
      p = q;
    }
  }
  // A lane's height: its name's (CSS --lane: taller on a phone, where a finger taps it).
  function laneHeight() { return parseFloat(getComputedStyle($("laneBox")).getPropertyValue("--lane")) || 14; }
  function drawLanes() {
    lane = laneHeight();
    var lanes = Math.max(1, runs.length + (D.compare ? 1 : 0)), event = +$("event").value;
    canvas.width = Math.max(200, Math.floor(canvas.clientWidth) || 1000);
    canvas.height = lanes * lane + 4;
    canvas.style.height = canvas.height + "px";
    ctx.fillStyle = "#fff";
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    runs.forEach(function (run, k) {
      paintLane(k * lane + 2, run.kept + 1, function (i) { return priority(run, i, event); });
    });
    if (D.compare) paintLane(runs.length * lane + 2, last + 1, function (i) { return differs[i] ? 5 : 0; });
    paintMarks();
    strip = ctx.getImageData(0, 0, canvas.width, canvas.height);
    $("zoomLabel").textContent = runs.length ? "steps " + stepNumber(Math.max(0, Math.ceil(range.from))) + " to " +
      stepNumber(Math.min(last, Math.floor(range.from + range.span))) + " of " + stepNumber(last) : "";
    drawChart();
  }
  function drawCursor() {
    if (!strip) return;
    ctx.putImageData(strip, 0, 0);
    var x = Math.round(xOf(view.i));
    ctx.strokeStyle = "#ff8f00";
    ctx.lineWidth = 2;
    ctx.strokeRect(0, view.robot * lane + 1, canvas.width, lane - 1);
    ctx.fillStyle = "#000";
    if (x >= 0 && x <= canvas.width) ctx.fillRect(Math.min(x, canvas.width - 2), 0, 2, canvas.height);
    if (chartStrip) {
      chartCtx.putImageData(chartStrip, 0, 0);
      chartCtx.fillStyle = "#000";
      if (x >= 0 && x <= chart.width) chartCtx.fillRect(Math.min(x, chart.width - 2), 0, 2, chart.height);
    }
  }
  function zoom(factor, centre) {         // the range shown, scaled by factor around the index centre
    var span = Math.round(Math.max(Math.min(last, 8), Math.min(last, range.span * factor))) || 1;
    var from = centre - (centre - range.from) * span / range.span;
    range.span = span;
    pan(from);
  }
  function pan(from) {                    // whole steps: the range's ends are steps
    range.from = Math.max(0, Math.min(last - range.span, Math.round(from)));
    drawLanes();
    drawCursor();
  }

  // Robots per state of one supervisor over the range shown: per pixel column, the robots in
  // each state stacked, one colour per state (the legend names them, and the counts at the step
  // shown).
  var chart = $("chart"), chartCtx = chart.getContext("2d"), chartStrip = null;
  var PALETTE = ["#1e88e5", "#fb8c00", "#43a047", "#e53935", "#8e24aa", "#00acc1", "#fdd835", "#6d4c41",
    "#546e7a", "#d81b60"];
  function stateColour(q) { return PALETTE[q % PALETTE.length]; }
  function countsAt(s, i) {
    var count = [];
    for (var q = 0; q < D.supervisors[s]; q++) count.push(0);
    runs.forEach(function (run) { count[vectorOf(run, i)[s]]++; });
    return count;
  }
  function drawChart() {
    if (!runs.length) { $("chartBox").hidden = true; return; }
    var s = +$("chartSup").value, width = canvas.width, height = chart.height, seen = {};
    chart.width = width;
    chart.style.height = height + "px";
    chartCtx.fillStyle = "#fff";
    chartCtx.fillRect(0, 0, width, height);
    for (var x = 0; x < width; x++) {
      var i = indexAt((x + 0.5) / width);
      if (i < 0 || i > last) continue;
      var count = countsAt(s, i), y = height;
      for (var q = 0; q < count.length; q++) {
        if (!count[q]) continue;
        var h = count[q] * height / runs.length;
        seen[q] = true;
        chartCtx.fillStyle = stateColour(q);
        chartCtx.fillRect(x, y - h, 1, h);
        y -= h;
      }
    }
    chartStrip = chartCtx.getImageData(0, 0, width, height);
    var legend = $("chartLegend");
    legend.textContent = "";
    Object.keys(seen).forEach(function (q) {
      var key = el("span", "q" + q, "state");
      key.style.borderLeftColor = stateColour(+q);
      legend.appendChild(key);
    });
  }
  function drawChartNow() {
    if (!runs.length) return;
    var count = countsAt(+$("chartSup").value, view.i), said = [];
    count.forEach(function (n, q) { if (n) said.push("q" + q + " \u00d7" + n); });
    $("chartNow").textContent = (view.i ? "step " + stepNumber(view.i) : "step 0") + ": " + said.join(", ");
  }

  // Marks (docs/inspect.md, "The timeline"): steps the user marks with m or the mark button,
  // drawn on the timeline (a purple line over the lanes, a flag on top), listed beside its
  // buttons, visited with . and , (next / previous), and kept in the page's address
  // (#step=N&robot=R&marks=12,40) so that a link shares them. Step numbers as the traces number
  // them, sorted; a mark outside the steps this page keeps stays in the address, not drawn.
  var stepMarks = [], marksListed = null;
  function parseMarks(text) {
    var seen = {};
    text.split(",").forEach(function (n) { if (/^\d+$/.test(n)) seen[+n] = true; });
    return Object.keys(seen).map(Number).sort(function (a, b) { return a - b; });
  }
  function inWindow(n) { return n - D.first + 1 >= 0 && n - D.first + 1 <= last; }
  function toggleMark() {
    var n = stepNumber(view.i), k = stepMarks.indexOf(n);
    if (k >= 0) stepMarks.splice(k, 1); else stepMarks = parseMarks(stepMarks.concat([n]).join(","));
    drawLanes();
    render();
  }
  function seekMark(direction) {
    var now = stepNumber(view.i), list = stepMarks.filter(inWindow);
    if (direction < 0) list.reverse();
    var to = list.find(function (n) { return direction > 0 ? n > now : n < now; });
    if (to === undefined) $("status").textContent = "no " + (direction > 0 ? "next" : "previous") + " mark";
    else go(to - D.first + 1);
  }
  function paintMarks() {
    ctx.fillStyle = "#6a1b9a";
    stepMarks.forEach(function (n) {
      var x = Math.round(xOf(n - D.first + 1));
      if (!inWindow(n) || x < 0 || x > canvas.width) return;
      x = Math.min(x, canvas.width - 2);
      ctx.fillRect(x, 0, 2, canvas.height);
      ctx.beginPath();
      ctx.moveTo(x + 2, 0);
      ctx.lineTo(x + 9, 4);
      ctx.lineTo(x + 2, 8);
      ctx.fill();
    });
  }
  function drawMarks() {                   // the mark button says what it does here; the list, when changed
    var here = stepMarks.indexOf(stepNumber(view.i)) >= 0, list = $("markList");
    $("mark").textContent = here ? "unmark" : "mark";
    $("mark").classList.toggle("marked", here);
    if (stepMarks.join(",") === marksListed) return;
    marksListed = stepMarks.join(",");
    list.textContent = "";
    stepMarks.forEach(function (n) {
      var button = el("button", String(n));
      button.disabled = !inWindow(n);
      button.title = inWindow(n) ? "go to step " + n : "step " + n + " is not among the steps this page keeps";
      button.addEventListener("click", function () { go(n - D.first + 1); });
      list.appendChild(button);
    });
  }

  function render() {
    $("slider").value = String(view.i);
    $("stepLabel").textContent = view.i === 0 ? (D.first === 1 ? "reset" : "before step " + D.first) :
      "step " + stepNumber(view.i) + " of " + stepNumber(last);
    document.body.dataset.step = String(stepNumber(view.i));
    document.body.dataset.robot = String(view.robot);
    if (view.i < range.from || view.i > range.from + range.span) pan(view.i - range.span / 2);
    drawGraphs();
    var panels = $("panels");
    panels.textContent = "";
    (D.compare ? [0, 1] : runs.length ? [view.robot] : []).forEach(function (k) { panels.appendChild(panel(k)); });
    if (!runs.length) panels.appendChild(el("p", "No trace given: the supervisors in their initial states."));
    drawLog();
    drawSim();
    drawCursor();
    drawChartNow();
    drawMarks();
    document.querySelectorAll("#laneNames span").forEach(function (s, k) {
      s.classList.toggle("selected", k === view.robot);
    });
    clearTimeout(hashTimer);               // the URL follows once the view rests (a browser ignores
    hashTimer = setTimeout(writeHash, 100); // a flood of history calls, as playing would make)
  }
  var hashTimer = null;
  function writeHash() {
    var hash = "#step=" + stepNumber(view.i) + (runs.length ? "&robot=" + encodeURIComponent(runs[view.robot].name) : "") +
      (stepMarks.length ? "&marks=" + stepMarks.join(",") : "");
    if (location.hash !== hash) history.replaceState(null, "", hash);
  }

  function go(i) { leaveSim(); view.i = Math.max(0, Math.min(last, i)); $("status").textContent = ""; render(); }
  function robot(k) { if (runs.length) { leaveSim(); view.robot = (k + runs.length) % runs.length; render(); } }
  // What seek looks for: a search ({ name, test }), "violation" or an event (-1: any).
  function matcher(what) {
    if (typeof what === "object") return what;
    return { name: what === "violation" ? "violation" : what < 0 ? "event" : "EV_" + events[what][0],
      test: function (run, i) { return occurred(run, i, what); } };
  }
  function seek(what, direction) {
    // The robot shown's next (direction 1) or previous (-1) step where what occurred; when it has
    // none, the nearest such step of another robot (the first in lane order at that step); when
    // no robot has one, the view stays and #status says so.
    var m = matcher(what), which = (direction > 0 ? "next " : "previous ") + m.name, i, k, shown = runs[view.robot];
    if (!shown) return false;
    for (i = view.i + direction; i >= 1 && i <= last; i += direction) {
      if (m.test(shown, i)) { go(i); return true; }
    }
    for (i = view.i + direction; i >= 1 && i <= last; i += direction) {
      for (k = 0; k < runs.length; k++) {
        if (k !== view.robot && m.test(runs[k], i)) {
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
  function nextDifference(direction) {
    if (!D.compare) return;
    for (var i = view.i + direction; i >= 1 && i <= last; i += direction) if (differs[i]) { go(i); return; }
    $("status").textContent = "no " + (direction > 0 ? "next" : "previous") + " difference in the steps shown";
  }
  function goToStep() {        // the go-to box holds a step number as the traces number them
    var value = $("goto").value.trim();
    if (/^\d+$/.test(value)) go(+value - D.first + 1);
    else $("status").textContent = "go to: " + value + " is not a step number";
  }
  // The find box: "EV_x" (or "x"), the steps where event x fires; "S=qN" (or "S=N"), the steps
  // where supervisor S enters state N.
  function parseFind(text) {
    var m = /^\s*(\d+)\s*[=:]\s*q?(\d+)\s*$/.exec(text);
    if (m) {
      var s = +m[1], q = +m[2];
      if (s >= nSup || q >= D.supervisors[s]) return null;
      return { name: "supervisor " + s + " entering q" + q, test: function (run, i) {
        return i >= 1 && i <= run.kept && vectorOf(run, i)[s] === q && vectorOf(run, i - 1)[s] !== q; } };
    }
    var name = text.trim().replace(/^EV_/, ""), e = events.findIndex(function (ev) { return ev[0] === name; });
    return e < 0 ? null : matcher(e);
  }
  function find(direction) {
    var text = $("find").value, parsed = text.trim() ? parseFind(text) : null;
    if (text.trim() && !parsed) { $("status").textContent = "find: " + text + " is no event (EV_x) nor state (S=qN)"; }
    if (!found || !parsed || found.name !== parsed.name) { found = parsed; drawLanes(); drawCursor(); }
    if (found) seek(found, direction);
  }
  // #step=N&robot=NAME (or a lane number) in the URL: the step and robot to show.
  function fromHash() {
    var fields = {};
    location.hash.replace(/^#/, "").split("&").forEach(function (pair) {
      var cut = pair.indexOf("=");
      try { if (cut > 0) fields[pair.slice(0, cut)] = decodeURIComponent(pair.slice(cut + 1)); } catch (err) { }
    });
    if (fields.robot !== undefined) {
      var k = runs.findIndex(function (run) { return run.name === fields.robot; });
      if (k < 0 && /^\d+$/.test(fields.robot) && +fields.robot < runs.length) k = +fields.robot;
      if (k >= 0) view.robot = k;
    }
    stepMarks = parseMarks(fields.marks || "");
    if (/^\d+$/.test(fields.step || "")) view.i = Math.max(0, Math.min(last, +fields.step - D.first + 1));
  }

  // The static parts: summary, event list, lanes' names, whole runs.
  var total = runs.reduce(function (n, r) { return n + r.steps; }, 0);
  var kept = runs.reduce(function (n, r) { return n + r.kept; }, 0);
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
    ["difference", "prevDifference", "nextDifference"].forEach(function (id) { $(id).hidden = false; });
  }
  $("summary").textContent = summary;
  events.forEach(function (ev, e) {
    var option = el("option", "EV_" + ev[0] + (ev[1] === "c" ? " (controllable)" : " (uncontrollable)"));
    option.value = String(e);
    $("event").appendChild(option);
  });
  runs.forEach(function (run, k) {
    var s = el("span", run.name, "lane");
    s.title = run.name;
    s.addEventListener("click", function () { robot(k); });
    $("laneNames").appendChild(s);
  });
  if (D.compare) $("laneNames").appendChild(el("span", "differences", "lane differences"));
  $("lanes").hidden = !runs.length;
  D.supervisors.forEach(function (states, s) {
    var option = el("option", "supervisor " + s);
    option.value = String(s);
    $("chartSup").appendChild(option);
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
  $("prevDifference").addEventListener("click", function () { nextDifference(-1); });
  $("nextDifference").addEventListener("click", function () { nextDifference(1); });
  $("zoomIn").addEventListener("click", function () { zoom(1 / 2, view.i); });
  $("zoomOut").addEventListener("click", function () { zoom(2, view.i); });
  $("zoomAll").addEventListener("click", function () { range.from = 0; zoom(last / range.span, 0); });
  $("mark").addEventListener("click", toggleMark);
  $("prevMark").addEventListener("click", function () { seekMark(-1); });
  $("nextMark").addEventListener("click", function () { seekMark(1); });
  $("goto").addEventListener("keydown", function (e) { if (e.key === "Enter") { goToStep(); $("goto").blur(); } });
  $("find").addEventListener("keydown", function (e) { if (e.key === "Enter") find(e.shiftKey ? -1 : 1); });
  $("findNext").addEventListener("click", function () { find(1); });
  $("simStep").addEventListener("click", simStep);
  $("simUndo").addEventListener("click", simUndo);
  $("simReset").addEventListener("click", simReset);
  $("simSave").addEventListener("click", simSave);
  // A seed or policy changed, the VM's choices are others: the simulation starts again.
  ["simSeed", "simPolicy"].forEach(function (id) {
    $(id).addEventListener("change", function () {
      if (sim) { startSim(); $("simStatus").textContent = "seed or policy changed: the simulation started again"; }
      render();
    });
  });
  // A choice made, the keys go back to the page's shortcuts.
  $("event").addEventListener("change", function () { $("event").blur(); drawLanes(); render(); });
  $("chartSup").addEventListener("change", function () { $("chartSup").blur(); drawChart(); render(); });
  $("filter").addEventListener("change", render);
  $("depth").addEventListener("change", function () { $("depth").blur(); render(); });
  $("speed").addEventListener("change", function () { $("speed").blur(); if (view.timer) { play(); play(); } });
  // On the timeline: a click shows that robot at that step, a drag pans, Ctrl+wheel zooms.
  var drag = null;
  canvas.addEventListener("mousedown", function (e) { drag = { x: e.clientX, from: range.from, moved: false }; });
  window.addEventListener("mousemove", function (e) {
    if (!drag) return;
    var box = canvas.getBoundingClientRect();
    if (Math.abs(e.clientX - drag.x) > 3) drag.moved = true;
    if (drag.moved) pan(drag.from - (e.clientX - drag.x) * range.span / box.width);
  });
  window.addEventListener("mouseup", function (e) {
    if (!drag) return;
    var moved = drag.moved, box = canvas.getBoundingClientRect();
    drag = null;
    if (moved || e.target !== canvas) return;
    var k = Math.floor((e.clientY - box.top) / lane);
    if (k >= 0 && k < runs.length && k !== view.robot) { leaveSim(); view.robot = k; }
    go(indexAt((e.clientX - box.left) / box.width));
  });
  canvas.addEventListener("wheel", function (e) {          // with Ctrl: the wheel alone scrolls the page
    var box = canvas.getBoundingClientRect();
    if (!e.ctrlKey) return;
    e.preventDefault();
    zoom(e.deltaY > 0 ? 1.5 : 1 / 1.5, indexAt((e.clientX - box.left) / box.width));
  }, { passive: false });
  window.addEventListener("resize", function () { drawLanes(); drawCursor(); });
  window.addEventListener("hashchange", function () { leaveSim(); fromHash(); drawLanes(); render(); });
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
    d: function () { nextDifference(1); },
    D: function () { nextDifference(-1); },
    z: function () { zoom(1 / 2, view.i); },
    Z: function () { zoom(2, view.i); },
    g: function () { $("goto").focus(); $("goto").select(); },     // what is typed replaces what was there
    "/": function () { $("find").focus(); $("find").select(); },
    n: simStep,
    u: simUndo,
    m: toggleMark,
    ".": function () { seekMark(1); },
    ",": function () { seekMark(-1); }
  };
  document.addEventListener("keydown", function (e) {
    var action = keys[e.key], target = e.target;
    var typing = target.tagName === "SELECT" || (target.tagName === "INPUT" && /^(number|search|text)$/.test(target.type));
    if (typing && e.key === "Escape") { target.blur(); return; }      // back to the page's keys
    if (!action || e.ctrlKey || e.altKey || e.metaKey || typing) return;
    e.preventDefault();
    action(e);
  });
  fromHash();
  drawLanes();
  render();
  document.body.dataset.ready = "1";
})();
