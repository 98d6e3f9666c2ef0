// jdraw's page: draw or drop an image, POST it to /api/plan, animate the plan, offer the files.
// Plain script, no libraries: it runs offline from the package's static folder.
"use strict";

const $ = (id) => document.getElementById(id);
const pad = $("pad");
const padCtx = pad.getContext("2d");
const view = $("view");
const viewCtx = view.getContext("2d");

// What is planned: the drawing on the pad, or a chosen file (sent as it is, byte for byte).
let chosenFile = null;
let padDrawn = false;
let lastPlan = null; // {image: Blob, name, json, strokes, background}
let anim = null;

function setState(state) {
  document.body.dataset.state = state;
}

function showError(message) {
  const box = $("error");
  box.textContent = message;
  box.hidden = false;
  setState("error");
}

function clearError() {
  $("error").hidden = true;
  $("error").textContent = "";
}

// ---------------------------------------------------------------- the drawing pad

function clearPad() {
  padCtx.fillStyle = "#fff";
  padCtx.fillRect(0, 0, pad.width, pad.height);
  padDrawn = false;
}

function padPoint(e) {
  const r = pad.getBoundingClientRect();
  return [((e.clientX - r.left) * pad.width) / r.width, ((e.clientY - r.top) * pad.height) / r.height];
}

let penDown = false;
let lastPoint = null;

pad.addEventListener("pointerdown", (e) => {
  if (e.button !== 0) return;
  e.preventDefault();
  pad.setPointerCapture(e.pointerId);
  penDown = true;
  lastPoint = padPoint(e);
  padCtx.strokeStyle = "#000";
  padCtx.fillStyle = "#000";
  padCtx.lineWidth = 6;
  padCtx.lineCap = "round";
  padCtx.lineJoin = "round";
  padCtx.beginPath();
  padCtx.arc(lastPoint[0], lastPoint[1], 3, 0, 2 * Math.PI);
  padCtx.fill();
  padDrawn = true;
});

pad.addEventListener("pointermove", (e) => {
  if (!penDown) return;
  e.preventDefault();
  const events = e.getCoalescedEvents ? e.getCoalescedEvents() : [e];
  for (const ev of events.length ? events : [e]) {
    const p = padPoint(ev);
    padCtx.beginPath();
    padCtx.moveTo(lastPoint[0], lastPoint[1]);
    padCtx.lineTo(p[0], p[1]);
    padCtx.stroke();
    lastPoint = p;
  }
});

for (const type of ["pointerup", "pointercancel"]) {
  pad.addEventListener(type, () => {
    penDown = false;
  });
}

function useDrawing() {
  chosenFile = null;
  $("preview").hidden = true;
  $("drop-hint").hidden = false;
  pad.hidden = false;
  $("input-name").textContent = "your drawing";
}

$("clear").addEventListener("click", () => {
  clearPad();
  useDrawing();
  clearError();
});

// ---------------------------------------------------------------- choosing or dropping a file

function chooseFile(file) {
  if (!file) return;
  chosenFile = file;
  const preview = $("preview");
  if (preview.src) URL.revokeObjectURL(preview.src);
  preview.src = URL.createObjectURL(file);
  preview.hidden = false;
  $("drop-hint").hidden = true;
  pad.hidden = true;
  $("input-name").textContent = `${file.name} (${formatBytes(file.size)})`;
  plan();
}

$("file").addEventListener("change", (e) => {
  chooseFile(e.target.files[0]);
  e.target.value = "";
});

const zone = $("drop-zone");
zone.addEventListener("dragover", (e) => {
  e.preventDefault();
  zone.classList.add("over");
});
zone.addEventListener("dragleave", () => zone.classList.remove("over"));
zone.addEventListener("drop", (e) => {
  e.preventDefault();
  zone.classList.remove("over");
  if (e.dataTransfer.files.length) chooseFile(e.dataTransfer.files[0]);
});

function formatBytes(n) {
  if (n < 1e3) return `${n} B`;
  if (n < 1e6) return `${(n / 1e3).toFixed(1)} kB`;
  return `${(n / 1e6).toFixed(1)} MB`;
}

// ---------------------------------------------------------------- planning

function padBlob() {
  return new Promise((resolve) => pad.toBlob(resolve, "image/png"));
}

function formFor(image, name) {
  const form = new FormData();
  form.append("image", image, name);
  for (const el of $("options").elements) {
    if (el.name && el.value.trim() !== "") form.append(el.name, el.value.trim());
  }
  return form;
}

async function request(format, image, name) {
  const res = await fetch(`/api/plan?format=${format}`, { method: "POST", body: formFor(image, name) });
  const text = await res.text();
  if (!res.ok) {
    let message = text;
    try {
      message = JSON.parse(text).error;
    } catch (_) {
      // not JSON: a proxy's page; show its first line
      message = text.split("\n")[0] || res.statusText;
    }
    throw new Error(`${res.status}: ${message}`);
  }
  return text;
}

function stem(name) {
  return name.replace(/\.[^.]*$/, "") || "drawing";
}

function setDownload(id, text, type, filename) {
  const a = $(id);
  if (a.href && a.href.startsWith("blob:")) URL.revokeObjectURL(a.href);
  a.href = URL.createObjectURL(new Blob([text], { type }));
  a.download = filename;
  a.classList.remove("disabled");
  a.removeAttribute("aria-disabled");
}

function disableDownloads() {
  for (const id of ["dl-svg", "dl-gcode", "dl-json"]) {
    const a = $(id);
    a.removeAttribute("href");
    a.classList.add("disabled");
    a.setAttribute("aria-disabled", "true");
  }
}

let planning = false;

async function plan() {
  if (planning) return;
  clearError();
  let image, name;
  if (chosenFile) {
    image = chosenFile;
    name = chosenFile.name;
  } else if (padDrawn) {
    image = await padBlob();
    name = "drawing.png";
  } else {
    showError("Draw something on the pad, or choose an image, first.");
    return;
  }
  planning = true;
  $("plan").disabled = true;
  setState("planning");
  $("status").textContent = "Planning… (the server's first plan waits for the model to compile)";
  const started = performance.now();
  try {
    const json = await request("json", image, name);
    const data = JSON.parse(json);
    const seconds = ((performance.now() - started) / 1000).toFixed(1);
    $("status").textContent = `Planned in ${seconds} s.`;
    lastPlan = { image, name, data, background: await backgroundFor(image) };
    showStats(data.stats);
    setDownload("dl-json", json, "application/json", `${stem(name)}.json`);
    startAnimation(lastPlan);
    await fetchFiles(image, name);
  } catch (err) {
    $("status").textContent = "";
    showError(`Could not plan ${name}: ${err.message}`);
  } finally {
    planning = false;
    $("plan").disabled = false;
  }
}

// The SVG and G-code of the plan just made: the server keeps the plan, so these do not replan.
async function fetchFiles(image, name) {
  const [svg, gcode] = await Promise.all([request("svg", image, name), request("gcode", image, name)]);
  setDownload("dl-svg", svg, "image/svg+xml", `${stem(name)}.svg`);
  setDownload("dl-gcode", gcode, "text/plain", `${stem(name)}.gcode`);
  document.body.dataset.files = "ready";
}

// A new size or preset changes the files and the statistics, not the strokes.
async function refreshFiles() {
  if (!lastPlan || planning) return;
  clearError();
  disableDownloads();
  document.body.dataset.files = "";
  try {
    const json = await request("json", lastPlan.image, lastPlan.name);
    showStats(JSON.parse(json).stats);
    setDownload("dl-json", json, "application/json", `${stem(lastPlan.name)}.json`);
    await fetchFiles(lastPlan.image, lastPlan.name);
    if (document.body.dataset.state === "error") setState(anim && anim.finished ? "done" : "animating");
  } catch (err) {
    showError(`Could not update the files: ${err.message}`);
  }
}

$("options").addEventListener("change", (e) => {
  if (e.target.name === "polarity") {
    if (lastPlan) plan();
  } else {
    refreshFiles();
  }
});
$("options").addEventListener("submit", (e) => e.preventDefault());
$("plan").addEventListener("click", () => {
  disableDownloads();
  plan();
});

function formatTime(s) {
  if (s < 60) return `~${Math.round(s)} s`;
  const total = Math.round(s);
  const m = Math.floor(total / 60);
  if (m < 60) return `~${m} min ${String(total % 60).padStart(2, "0")} s`;
  return `~${Math.floor(m / 60)} h ${String(m % 60).padStart(2, "0")} min`;
}

function showStats(stats) {
  const unit = stats.units;
  $("stat-strokes").textContent = String(stats.strokes);
  $("stat-down").textContent = `${stats.pen_down.toFixed(1)} ${unit}`;
  $("stat-up").textContent = `${stats.pen_up.toFixed(1)} ${unit}`;
  $("stat-time").textContent =
    formatTime(stats.time_s) + (unit === "mm" ? "" : " (G-code 100 mm wide; set a width)");
}

async function backgroundFor(image) {
  try {
    return await createImageBitmap(image);
  } catch (_) {
    return null;
  }
}

// ---------------------------------------------------------------- the animation

const TRAVEL_SPEED = 3; // pen-up moves run this many times faster than drawing (as --gif)
const FAINT = "rgb(170,170,170)";

function strokeColour(i, n) {
  const hue = n > 1 ? 240 - (240 * i) / (n - 1) : 240; // blue first, red last
  return `hsl(${hue}, 85%, 42%)`;
}

function pathLength(points) {
  let d = 0;
  for (let k = 1; k < points.length; k++) {
    d += Math.hypot(points[k][0] - points[k - 1][0], points[k][1] - points[k - 1][1]);
  }
  return d;
}

// The motion at constant pen speed: pen-up moves and strokes, each with a start and end time.
function timeline(strokes) {
  const moves = [];
  let t = 0;
  let prev = null;
  strokes.forEach((s, i) => {
    if (prev) {
      const d = Math.hypot(s[0][0] - prev[0], s[0][1] - prev[1]) / TRAVEL_SPEED;
      moves.push({ t0: t, t1: t + d, points: [prev, s[0]], stroke: -1 });
      t += d;
    }
    const d = Math.max(pathLength(s), 1);
    moves.push({ t0: t, t1: t + d, points: s, stroke: i });
    t += d;
    prev = s[s.length - 1];
  });
  return { moves, total: t };
}

// The part of a polyline drawn by time `at`, moving at constant speed over [t0, t1].
function partial(points, t0, t1, at) {
  if (points.length < 2 || at >= t1) return points;
  const want = ((at - t0) / (t1 - t0)) * pathLength(points);
  const out = [points[0]];
  let done = 0;
  for (let k = 1; k < points.length; k++) {
    const a = points[k - 1];
    const b = points[k];
    const seg = Math.hypot(b[0] - a[0], b[1] - a[1]);
    if (done + seg >= want) {
      const f = seg > 0 ? (want - done) / seg : 0;
      out.push([a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])]);
      return out;
    }
    out.push(b);
    done += seg;
  }
  return out;
}

// The strokes' bounding box with a margin, in input pixels (the view is cropped to it).
function cropBox(data) {
  let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
  for (const s of data.strokes) {
    for (const [x, y] of s) {
      x0 = Math.min(x0, x); y0 = Math.min(y0, y); x1 = Math.max(x1, x); y1 = Math.max(y1, y);
    }
  }
  if (!isFinite(x0)) return [0, 0, data.width, data.height];
  const pad = Math.max(4, 0.06 * Math.max(x1 - x0, y1 - y0));
  return [
    Math.max(0, x0 - pad), Math.max(0, y0 - pad),
    Math.min(data.width, x1 + pad + 1), Math.min(data.height, y1 + pad + 1),
  ];
}

function startAnimation(p) {
  if (anim) cancelAnimationFrame(anim.frame);
  const { moves, total } = timeline(p.data.strokes);
  const n = p.data.strokes.length;
  const box = cropBox(p.data);
  const side = 480;
  const k = side / Math.max(box[2] - box[0], box[3] - box[1]);
  view.width = Math.max(1, Math.round((box[2] - box[0]) * k));
  view.height = Math.max(1, Math.round((box[3] - box[1]) * k));
  // As --gif: 3 frames a stroke at 60 ms, from 60 to 240 frames.
  const duration = Math.min(240, Math.max(60, 3 * n)) * 60;
  anim = { p, moves, total, n, box, k, duration, at: 0, playing: true, finished: false, frame: 0, last: null };
  $("play").disabled = false;
  $("scrub").disabled = false;
  $("play").textContent = "Pause";
  setState("animating");
  anim.frame = requestAnimationFrame(tick);
}

function tick(now) {
  if (!anim.playing) return;
  if (anim.last !== null) anim.at = Math.min(1, anim.at + (now - anim.last) / anim.duration);
  anim.last = now;
  render(anim.at);
  if (anim.at >= 1) {
    finish();
    return;
  }
  anim.frame = requestAnimationFrame(tick);
}

function finish() {
  anim.playing = false;
  anim.finished = true;
  anim.last = null;
  $("play").textContent = "Replay";
  if (document.body.dataset.state !== "error") setState("done");
}

function render(fraction) {
  const { p, moves, total, n, box, k } = anim;
  const at = fraction * total;
  $("scrub").value = String(Math.round(fraction * 1000));
  const ctx = viewCtx;
  const lw = Math.max(2, Math.round(view.width / 240));
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.fillStyle = "#fff";
  ctx.fillRect(0, 0, view.width, view.height);
  if (p.background) {
    ctx.globalAlpha = 0.22;
    ctx.drawImage(p.background, box[0], box[1], box[2] - box[0], box[3] - box[1], 0, 0, view.width, view.height);
    ctx.globalAlpha = 1;
  }
  // Input pixel centres are at integers: (x + 0.5) maps to the middle of its pixel.
  ctx.setTransform(k, 0, 0, k, (0.5 - box[0]) * k, (0.5 - box[1]) * k);
  ctx.lineCap = "round";
  ctx.lineJoin = "round";
  let tip = null;
  for (const m of moves) {
    if (m.t0 > at && !(fraction >= 1)) break;
    const current = at < m.t1 && fraction < 1;
    const pts = current ? partial(m.points, m.t0, m.t1, at) : m.points;
    if (m.stroke < 0) {
      polyline(ctx, pts, FAINT, 1 / k);
    } else {
      const colour = current ? "rgb(20,20,20)" : strokeColour(m.stroke, n);
      polyline(ctx, pts, colour, (current ? lw + 2 : lw) / k);
      dot(ctx, m.points[0], (lw + 1.5) / k, strokeColour(m.stroke, n));
    }
    tip = pts[pts.length - 1];
    if (current) break;
  }
  if (tip && fraction < 1) dot(ctx, tip, (lw + 3) / k, "rgb(230,30,30)");
}

function polyline(ctx, pts, colour, width) {
  ctx.strokeStyle = colour;
  ctx.lineWidth = width;
  ctx.beginPath();
  ctx.moveTo(pts[0][0], pts[0][1]);
  if (pts.length === 1) ctx.lineTo(pts[0][0] + 1e-3, pts[0][1]);
  for (let q = 1; q < pts.length; q++) ctx.lineTo(pts[q][0], pts[q][1]);
  ctx.stroke();
}

function dot(ctx, p, r, colour) {
  ctx.fillStyle = colour;
  ctx.beginPath();
  ctx.arc(p[0], p[1], r, 0, 2 * Math.PI);
  ctx.fill();
}

$("play").addEventListener("click", () => {
  if (!anim) return;
  if (anim.playing) {
    anim.playing = false;
    anim.last = null;
    $("play").textContent = "Play";
    return;
  }
  if (anim.finished) anim.at = 0;
  anim.finished = false;
  anim.playing = true;
  $("play").textContent = "Pause";
  setState("animating");
  anim.frame = requestAnimationFrame(tick);
});

$("scrub").addEventListener("input", (e) => {
  if (!anim) return;
  anim.playing = false;
  anim.last = null;
  anim.at = Number(e.target.value) / 1000;
  anim.finished = anim.at >= 1;
  $("play").textContent = anim.finished ? "Replay" : "Play";
  render(anim.at);
});

// ---------------------------------------------------------------- start

async function loadOptions() {
  try {
    const res = await fetch("/api/options");
    const opts = await res.json();
    const select = $("preset");
    select.replaceChildren(...opts.presets.map((name) => new Option(name, name, name === "zaxis", name === "zaxis")));
    const mb = opts.limits.max_bytes / 1e6;
    const mpx = opts.limits.max_pixels / 1e6;
    $("drop-hint").textContent = `Draw here, or drop an image (up to ${mb} MB, ${mpx} Mpx)`;
  } catch (_) {
    // the page's own preset list stays
  }
}

clearPad();
loadOptions();
