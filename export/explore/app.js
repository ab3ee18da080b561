"use strict";
// The explorer page's script (export/explorer_page.h): the sliders, the canvas shading from
// the program's tables, the plots and the address. The formulas are colour.js's, the
// parsing of what a user types input.js's; this file holds the page's state and elements.
(() => {
const C = AlloyColour, I = AlloyInput;
const D = JSON.parse(document.getElementById("explorer-data").textContent);
const $ = (id) => document.getElementById(id);
const T = D.table;

// Elements are built from nodes: text from the data (names, paths, sources) only ever
// becomes text nodes or attribute values, never markup.
function build(node, attrs, children) {
  for (const [name, value] of Object.entries(attrs)) node.setAttribute(name, value);
  node.append(...children);
  return node;
}
const el = (tag, attrs = {}, ...children) => build(document.createElement(tag), attrs, children);
const SVG_NS = document.querySelector("svg").namespaceURI;  // the plots' own namespace
const svgEl = (tag, attrs = {}, ...children) => build(document.createElementNS(SVG_NS, tag), attrs, children);

// ---- Decoding the program's tables.
function bytes(b64) {
  const bin = atob(b64);
  const out = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
  return out;
}
const f32 = (b64) => { const u = bytes(b64); return new Float32Array(u.buffer, 0, u.length >> 2); };
const M = T.mu_nodes;
const muNodes = (r) => (r === 0 ? T.mu_nodes : T.rough_mu_nodes);
const ILLS = T.illuminants.map((ill) => ({
  name: ill.name, white: ill.white, xyz: ill.xyz.map(f32), sigma: ill.sigma ? f32(ill.sigma) : null,
}));
const SEGMENTS = T.segments.map((s) => ({ lo: s[0], hi: s[1], intervals: s[2], first: s[3] }));
const NL = T.lambda_nm.length;
const SPECTRA = { n: f32(T.n), k: f32(T.k), r: f32(T.r) };
const SIGMA_ANGLES = T.sigma_angles_deg;
const X_LO = D.x_range[0], X_HI = D.x_range[1];
const SYS = D.system;
const MATRIX = D.srgb_matrix;
const FINISHES = T.roughness;
const CTX = { sys: SYS, x_range: D.x_range, illuminants: ILLS.map((ill) => ill.name), roughness: FINISHES };

function decodeTile(t) {
  const size = t.size, cov = bytes(t.coverage);
  const nb = bytes(t.normals);
  const q = new Int16Array(nb.buffer, 0, nb.length >> 1);
  const nx = new Float32Array(size * size), ny = new Float32Array(size * size);
  const nz = new Float32Array(size * size).fill(1);
  for (let p = 0, j = 0; p < size * size; p++) {
    if (!cov[p]) continue;
    const x = q[j++] / 32767, y = q[j++] / 32767;
    nx[p] = x; ny[p] = y; nz[p] = Math.sqrt(Math.max(0, 1 - x * x - y * y));
  }
  return { size, cov, nx, ny, nz, light: {} };
}
const TILES = { sphere: decodeTile(D.tiles.sphere), ring: decodeTile(D.tiles.ring) };
const ENV = D.environment.map((m) => {
  const u = bytes(m.texels), q = new Uint16Array(u.buffer, 0, u.length >> 1);
  const e = new Float32Array(q.length);
  for (let i = 0; i < q.length; i++) e[i] = q[i] * m.scale;
  return { width: m.width, height: m.height, texels: e };
});

// E at each pixel of a tile for roughness r in studio light (mirror direction, bilinear
// in the latitude-longitude map as PrefilteredEnvironment::At reads its own).
function tileLight(tile, r) {
  if (tile.light[r]) return tile.light[r];
  const W = ENV[r].width, H = ENV[r].height, map = ENV[r].texels;
  const out = new Float32Array(tile.size * tile.size);
  for (let p = 0; p < out.length; p++) {
    if (!tile.cov[p]) continue;
    const z = tile.nz[p];
    const rx = 2 * z * tile.nx[p], ry = 2 * z * tile.ny[p], rz = 2 * z * z - 1;
    const theta = Math.acos(Math.min(1, Math.max(-1, ry)));
    let phi = Math.atan2(rz, rx);
    if (phi < 0) phi += 2 * Math.PI;
    const fy = Math.min(Math.max(theta * H / Math.PI - 0.5, 0), H - 1);
    const fx = phi * W / (2 * Math.PI) - 0.5;
    const j0 = Math.min(Math.floor(fy), H - 1), j1 = Math.min(j0 + 1, H - 1), ty = fy - j0;
    const fl = Math.floor(fx), tx = fx - fl;
    const i0 = ((fl % W) + W) % W, i1 = (i0 + 1) % W;
    const top = map[j0 * W + i0] + tx * (map[j0 * W + i1] - map[j0 * W + i0]);
    const bottom = map[j1 * W + i0] + tx * (map[j1 * W + i1] - map[j1 * W + i0]);
    out[p] = top + ty * (bottom - top);
  }
  tile.light[r] = out;
  return out;
}

// ---- Interpolating the tables.
function weightsAt(x) { return C.segmentWeights(C.findSegment(SEGMENTS, x), x); }
function rowAt(ill, r, x) { return C.rowAtX(SEGMENTS, ILLS[ill].xyz[r], 3 * muNodes(r), x); }
function spectrumAt(x) {
  const { first, w } = weightsAt(x), out = {};
  for (const key of ["n", "k", "r"]) {
    const src = SPECTRA[key], v = new Float64Array(NL);
    for (let q = 0; q < 4; q++) for (let l = 0; l < NL; l++) v[l] += w[q] * src[(first + q) * NL + l];
    out[key] = v;
  }
  return out;
}
function sigmaAt(ill, x, angle) {
  const s = ILLS[ill].sigma;
  return s ? C.nodeAngleLinear(s, SEGMENTS, SIGMA_ANGLES, x, angle) : null;
}

// ---- State, kept in the address.
const state = I.defaultView(CTX);
function readHash() {
  const { view, bad } = I.parseAddress(location.hash, CTX);
  Object.assign(state, view);
  document.body.dataset.badParameters = bad.join(",");
}
const stateString = () => I.formatAddress(state, CTX);
function writeHash() {
  const s = stateString();
  if (location.hash.replace(/^#/, "") !== s) history.replaceState(null, "", "#" + s);
  document.body.dataset.state = s;
}

// ---- Drawing.
function drawTile(canvas, tile, row, light) {
  const size = tile.size;
  if (canvas.width !== size) { canvas.width = size; canvas.height = size; }
  const ctx = canvas.getContext("2d");
  const img = ctx.createImageData(size, size), d = img.data;
  const m = MATRIX, nodes = row.length / 3;
  for (let p = 0; p < size * size; p++) {
    const cov = tile.cov[p];
    if (!cov) continue;
    const t = Math.min(Math.max(tile.nz[p], 0), 1) * (nodes - 1);
    const i = Math.min(Math.floor(t), nodes - 2), f = t - i, a = 3 * i;
    const e = light ? light[p] : 1;
    const X = e * (row[a] + f * (row[a + 3] - row[a]));
    const Y = e * (row[a + 1] + f * (row[a + 4] - row[a + 1]));
    const Z = e * (row[a + 2] + f * (row[a + 5] - row[a + 2]));
    const o = 4 * p;
    d[o] = C.srgb8(m[0][0] * X + m[0][1] * Y + m[0][2] * Z);
    d[o + 1] = C.srgb8(m[1][0] * X + m[1][1] * Y + m[1][2] * Z);
    d[o + 2] = C.srgb8(m[2][0] * X + m[2][1] * Y + m[2][2] * Z);
    d[o + 3] = cov;
  }
  ctx.putImageData(img, 0, 0);
  // Pixel samples for checking the page: the centre and a few fixed points (tile fractions).
  const points = [[0.5, 0.5], [0.5 + 0.45 * 0.5, 0.5], [0.5, 0.5 - 0.45 * 0.7], [0.5 - 0.45 * 0.86, 0.5], [0.5, 0.5 + 0.45 * 0.75]];
  const samples = points.map(([u, v]) => {
    const px = Math.min(size - 1, Math.floor(u * size)), py = Math.min(size - 1, Math.floor(v * size));
    return [px, py].concat(Array.from(ctx.getImageData(px, py, 1, 1).data));
  });
  canvas.dataset.samples = JSON.stringify(samples);
  canvas.dataset.centre = samples[0].slice(2).join(",");
}

function metal(x) {
  const row0 = rowAt(state.ill, 0, x);
  const xyz = C.xyzAtMu(row0, Math.max(0, Math.cos(state.angle * Math.PI / 180)));
  const lab = C.labFromXYZ(xyz, ILLS[state.ill].white);
  const linear = C.linearSRGBFromXYZ(MATRIX, xyz);
  const rgb8 = linear.map(C.srgb8);
  const row = state.rough === 0 ? row0 : rowAt(state.ill, state.rough, x);
  return { x, xyz, lab, linear, rgb8, hex: C.hex(rgb8), sigma: sigmaAt(state.ill, x, state.angle), row };
}

const fixed = (v, n) => (Math.abs(v) < 0.5 * Math.pow(10, -n) ? 0 : v).toFixed(n);
function fillCard(key, m) {
  const clipped = m.linear.some((v) => v < 0 || v > 1);
  const row = (label, id, text, data) => [el("dt", {}, label), el("dd", { id: key + "-" + id, "data-value": data }, text)];
  const swatch = el("div", { class: "swatch", id: key + "-swatch" });
  swatch.style.background = m.hex;
  $("card-" + key).replaceChildren(
    swatch,
    el("div", { class: "hexline" },
       el("div", { class: "hex", id: key + "-hex", "data-value": m.hex }, m.hex),
       el("div", { class: "cond" }, `${ILLS[state.ill].name}, ${D.observer}° observer, ${fixed(state.angle, 1)}° incidence, polished`)),
    el("dl", { class: "values" },
       ...row("sRGB 8-bit", "srgb8", m.rgb8.join(", ") + (clipped ? " (clipped)" : ""), m.rgb8.join(",")),
       ...row("linear sRGB", "linear", m.linear.map((v) => fixed(v, 4)).join("  "), m.linear.join(",")),
       ...row("CIELAB", "lab", "L* " + fixed(m.lab[0], 2) + "  a* " + fixed(m.lab[1], 2) + "  b* " + fixed(m.lab[2], 2), m.lab.join(",")),
       ...row("XYZ", "xyz", m.xyz.map((v) => fixed(v, 4)).join("  "), m.xyz.join(",")),
       ...row("uncertainty", "sigma",
              m.sigma === null ? "none (the " + D.method + " model has no error bar)" : "ΔE00 " + fixed(m.sigma, 3) + " (one sigma)",
              m.sigma === null ? "none" : m.sigma)));
}

function verdict(de) {
  if (de < 0.5) return "the same colour to the eye";
  if (de < 1) return "not distinguishable side by side";
  if (de < 2) return "barely distinguishable side by side, by a trained eye";
  if (de < 3.5) return "visible side by side";
  if (de < 5) return "clearly different side by side";
  return "different colours at a glance";
}

// ---- From colour to composition (as 'alloycolor match' and 'tolerance', on the tables):
// the match box moves slider A to the composition whose colour is closest to a target, and
// slider A shows the window within which the colour stays within ΔE00 1 of A's, both
// under the light source and at the angle shown.
const MATCH_SCAN_POINTS = 1001;       // color::kMatchScanPoints
const MATCH_MARGIN_DE00 = 1;          // other minima within this of the best are listed
const REACHABLE_DE00 = 1;             // color::kReachableDeltaE00
const TOLERANCE_DE00 = 1;
const TOLERANCE_STEP = 5e-4;          // color::kToleranceStep
function labAt(x) {
  const mu = Math.max(0, Math.cos(state.angle * Math.PI / 180));
  return C.labFromXYZ(C.xyzAtMu(rowAt(state.ill, 0, x), mu), ILLS[state.ill].white);
}
function findComposition() {
  const box = $("match-target"), out = $("match-result");
  const target = I.parseColourTarget(box.value);
  if (!target) {
    box.classList.add("bad");
    out.textContent = "type #rrggbb (8-bit sRGB) or L*, a*, b*";
    return;
  }
  box.classList.remove("bad");
  const lab = target.lab || C.labFromSRGB8(MATRIX, target.rgb8, ILLS[state.ill].white);
  const found = C.minimaOf((x) => C.deltaE00(lab, labAt(x)), X_LO, X_HI, MATCH_SCAN_POINTS, MATCH_MARGIN_DE00);
  const best = found[0], name = (m) => I.describeComposition(m.x, SYS).main;
  const others = found.slice(1).map((m) => `${name(m)} (ΔE00 ${fixed(m.value, 2)})`);
  out.replaceChildren(
    best.value > REACHABLE_DE00 ? `not reachable with ${SYS.a}-${SYS.b}: the closest is ` : "A: ",
    el("b", {}, name(best)), `, ΔE00 ${fixed(best.value, 2)} left`,
    others.length ? "; as close: " + others.join(", ") : "");
  out.dataset.matches = JSON.stringify(found.map((m) => ({ x_atomic: m.x, de00: m.value })));
  state.x = best.x;
  update();
}
function drawWindow(a) {
  const w = C.windowAround((x) => C.deltaE00(a.lab, labAt(x)), a.x, TOLERANCE_DE00, X_LO, X_HI, TOLERANCE_STEP);
  const span = X_HI - X_LO || 1, band = $("window-a");
  band.style.left = `calc(8px + ${(w.lo - X_LO) / span} * (100% - 16px))`;
  band.style.width = `calc(${(w.hi - w.lo) / span} * (100% - 16px))`;
  const lo = I.describeComposition(w.lo, SYS).main, hi = I.describeComposition(w.hi, SYS).main;
  band.title = `Within ΔE00 ${TOLERANCE_DE00} of A's colour (${ILLS[state.ill].name}, ${fixed(state.angle, 1)}°): ` +
    `${lo} to ${hi}` + (w.clippedLo || w.clippedHi ? " (clipped at the model's range)" : "");
  band.dataset.lo = w.lo;
  band.dataset.hi = w.hi;
  return w;
}

// ---- Plots.
function niceTicks(lo, hi, count) {
  const span = hi - lo || 1, raw = span / count, mag = Math.pow(10, Math.floor(Math.log10(raw)));
  const step = [1, 2, 2.5, 5, 10].map((s) => s * mag).find((s) => span / s <= count) || 10 * mag;
  const out = [];
  for (let v = Math.ceil(lo / step) * step; v <= hi + 1e-9 * span; v += step) out.push(+v.toFixed(10));
  return out;
}
function plot(svgId, label, key, curves) {
  const svg = $(svgId), W = 340, H = 230, L = 44, R = 10, TOP = 14, B = 34;
  const l0 = T.lambda_nm[0], l1 = T.lambda_nm[NL - 1];
  let lo = Infinity, hi = -Infinity;
  for (const c of curves) for (let i = 0; i < c.x.length; i++) {
    if (c.x[i] < l0 || c.x[i] > l1) continue;
    lo = Math.min(lo, c.y[i]); hi = Math.max(hi, c.y[i]);
  }
  if (key === "r") { lo = Math.min(lo, 0); hi = Math.min(1, Math.max(hi, 0.2)); }
  else lo = Math.min(lo, 0);
  const pad = 0.04 * (hi - lo || 1); hi += pad;
  const sx = (l) => L + (l - l0) / (l1 - l0) * (W - L - R);
  const sy = (v) => TOP + (hi - v) / (hi - lo) * (H - TOP - B);
  const nodes = [];
  for (const t of niceTicks(lo, hi, 5)) {
    nodes.push(svgEl("line", { class: "grid", x1: L, x2: W - R, y1: sy(t), y2: sy(t) }),
               svgEl("text", { x: L - 5, y: sy(t) + 4, "text-anchor": "end" }, String(t)));
  }
  for (const t of niceTicks(l0, l1, 5)) {
    nodes.push(svgEl("line", { class: "axis", x1: sx(t), x2: sx(t), y1: H - B, y2: H - B + 4 }),
               svgEl("text", { x: sx(t), y: H - B + 16, "text-anchor": "middle" }, String(t)));
  }
  nodes.push(svgEl("line", { class: "axis", x1: L, x2: W - R, y1: H - B, y2: H - B }),
             svgEl("text", { x: (L + W - R) / 2, y: H - 4, "text-anchor": "middle" }, "wavelength (nm)"),
             svgEl("text", { x: L + 6, y: TOP + 10, style: "fill:#ebe8e1;font-size:13px;font-weight:600" }, label));
  for (const c of curves) {
    const pts = [];
    for (let i = 0; i < c.x.length; i++) if (c.x[i] >= l0 && c.x[i] <= l1) pts.push(sx(c.x[i]).toFixed(1) + "," + sy(c.y[i]).toFixed(1));
    const line = svgEl("polyline", { class: c.cls, points: pts.join(" ") }, svgEl("title", {}, c.title));
    if (c.color) line.style.stroke = c.color;
    nodes.push(line);
  }
  svg.replaceChildren(...nodes);
}
// The colour across composition (the table's, at the light source and angle shown), its
// one-sigma beneath as a band, the training samples as ticks (suspects red), where to
// measure next as green triangles (the library's suggestions), and A's composition.
function drawCompositionChart(a) {
  const W = 1000, L = 50, R = 12, STRIP = 40, TOP = 6, PLOT = 86, BASE = TOP + STRIP + 8 + PLOT;
  const N = 200, sx = (x) => L + (x - X_LO) / (X_HI - X_LO || 1) * (W - L - R);
  const nodes = [];
  const xs = Array.from({ length: N + 1 }, (_, i) => X_LO + (X_HI - X_LO) * i / N);
  const colours = xs.map((x) => metal(x));
  for (let i = 0; i <= N; i++) {
    const x0 = i === 0 ? sx(xs[0]) : (sx(xs[i - 1]) + sx(xs[i])) / 2;
    const x1 = i === N ? sx(xs[N]) : (sx(xs[i]) + sx(xs[i + 1])) / 2;
    const r = svgEl("rect", { x: x0.toFixed(2), y: TOP, width: (x1 - x0 + 0.4).toFixed(2), height: STRIP });
    r.style.fill = colours[i].hex;
    nodes.push(r);
  }
  const sigmas = colours.map((m) => m.sigma);
  if (sigmas.every((v) => v !== null)) {
    const top = Math.max(...sigmas) * 1.1 || 1;
    const sy = (v) => BASE - v / top * PLOT;
    const pts = [sx(xs[0]).toFixed(1) + "," + BASE]
      .concat(xs.map((x, i) => sx(x).toFixed(1) + "," + sy(sigmas[i]).toFixed(1)), [sx(xs[N]).toFixed(1) + "," + BASE]);
    nodes.push(svgEl("polygon", { class: "band", points: pts.join(" ") }, svgEl("title", {}, "one-sigma ΔE00")));
    for (const t of [0, top / 2.2, top / 1.1]) {
      nodes.push(svgEl("text", { x: L - 5, y: sy(t) + 4, "text-anchor": "end" }, t.toPrecision(2)));
    }
  } else {
    nodes.push(svgEl("text", { x: (L + W - R) / 2, y: BASE - PLOT / 2, "text-anchor": "middle" }, D.no_error_bar));
  }
  nodes.push(svgEl("line", { class: "axis", x1: L, x2: W - R, y1: BASE, y2: BASE }));
  for (const s of D.training) {
    nodes.push(svgEl("line", { class: "sample-tick", x1: sx(s.x), x2: sx(s.x), y1: TOP + STRIP, y2: BASE },
                     svgEl("title", {}, "measured: " + s.file)));
  }
  for (const s of D.suspects) {
    nodes.push(svgEl("circle", { class: "suspect", cx: sx(s.x), cy: BASE, r: 6 }, svgEl("title", {}, "suspect: " + s.reason)));
  }
  D.suggestions.forEach((s, k) => {
    const x = sx(s.x);
    nodes.push(svgEl("polygon", { class: "suggestion", points: `${x},${BASE + 2} ${x - 7},${BASE + 14} ${x + 7},${BASE + 14}` },
                     svgEl("title", {}, `measure next (${k + 1}): ${I.describeComposition(s.x, SYS).main}`)),
               svgEl("text", { x, y: BASE + 26, "text-anchor": "middle" }, String(k + 1)));
  });
  nodes.push(svgEl("line", { class: "now", x1: sx(a.x), x2: sx(a.x), y1: TOP, y2: BASE }));
  $("composition-chart").replaceChildren(...nodes);
  $("composition-chart").dataset.suggestions = D.suggestions.length;
  $("chart-legend").replaceChildren(
    `The colour of the polished metal across composition (${ILLS[state.ill].name}, ${fixed(state.angle, 1)}°) and beneath it ` +
    (D.has_sigma ? "its one-sigma ΔE00 as a band" : "no band: " + D.no_error_bar) +
    "; ticks: the training samples" + (D.suspects.length ? ", red: suspect samples" : "") +
    (D.suggestions.length ? "; green triangles: where to measure next, " +
      D.suggestions.map((s) => I.describeComposition(s.x, SYS).main).join(", then ") : "") +
    "; dashed: A.");
}
function drawPlots(a, b) {
  const sa = spectrumAt(a.x), sb = spectrumAt(b.x);
  const labelA = "A " + I.describeComposition(a.x, SYS).main, labelB = "B " + I.describeComposition(b.x, SYS).main;
  for (const [id, key, label] of [["plot-n", "n", "n"], ["plot-k", "k", "k"], ["plot-r", "r", "R at normal incidence"]]) {
    const curves = D.samples.map((s) => ({ x: s.lambda_nm, y: s[key], cls: "sample" + (s.measured ? "" : " model"), title: s.label }));
    curves.push({ x: T.lambda_nm, y: sb[key], cls: "curve b", color: b.hex, title: labelB });
    curves.push({ x: T.lambda_nm, y: sa[key], cls: "curve", color: a.hex, title: labelA });
    plot(id, label, key, curves);
  }
  const measured = D.samples.length && D.samples[0].measured;
  const swatchA = el("i"), swatchB = el("i", { class: "dash" });
  swatchA.style.borderColor = a.hex;
  swatchB.style.borderColor = b.hex;
  $("legend").replaceChildren(swatchA, labelA, swatchB, labelB, el("i", { class: "sample" }),
    `${measured ? "measured samples" : "the model at its training compositions"} (hover for names). ${D.samples_note}`);
}

// ---- The page.
let pending = false;
function render() {
  pending = false;
  writeHash();
  const a = metal(state.x), b = metal(state.x2);
  const studio = state.light === "studio";
  for (const [key, m] of [["a", a], ["b", b]]) {
    for (const shape of ["sphere", "ring"]) {
      const tile = TILES[shape];
      drawTile($(shape + "-" + key), tile, m.row, studio ? tileLight(tile, state.rough) : null);
    }
    $("stage-" + key).classList.toggle("uniform", !studio);
    fillCard(key, m);
    const d = I.describeComposition(m.x, SYS);
    $(key + "-readout").replaceChildren(el("b", {}, d.main), " · " + d.rest);
    if (key === "a") {
      const w = drawWindow(m);
      $("a-readout").append(` · within ΔE00 ${TOLERANCE_DE00}: ${I.describeComposition(w.lo, SYS).main} to ${I.describeComposition(w.hi, SYS).main}`);
    }
    const input = $("x-" + key), text = $("x-" + key + "-text");
    if (Math.abs(parseFloat(input.value) - m.x) > 1e-12) input.value = m.x;
    if (document.activeElement !== text) { text.value = d.main; text.classList.remove("bad"); }
  }
  const de = C.deltaE00(a.lab, b.lab);
  $("de00").textContent = fixed(de, 2);
  $("de00").dataset.value = de;
  $("verdict").textContent = verdict(de);
  $("pair-a").style.background = a.hex;
  $("pair-b").style.background = b.hex;
  $("difference-note").textContent = `CIEDE2000 between A and B, polished, ${ILLS[state.ill].name}, ${fixed(state.angle, 1)}° incidence. ` +
    "Below 1: not distinguishable side by side; 1-2: a trained eye may see it; 2-3.5: visible; above 5: different colours.";
  for (const btn of document.querySelectorAll("#ill-buttons button")) btn.setAttribute("aria-pressed", btn.dataset.ill == state.ill);
  for (const btn of document.querySelectorAll("#light-buttons button")) btn.setAttribute("aria-pressed", btn.dataset.light === state.light);
  for (const btn of document.querySelectorAll("#finish-buttons button")) btn.setAttribute("aria-pressed", btn.dataset.rough == state.rough);
  if (document.activeElement !== $("angle-value")) $("angle-value").value = state.angle;
  $("angle").value = state.angle;
  drawPlots(a, b);
  drawCompositionChart(a);
  document.body.dataset.ready = "true";
}
function update() { if (!pending) { pending = true; requestAnimationFrame(render); } }

function setup() {
  const trainingNote = D.training.length + " training sample" + (D.training.length === 1 ? "" : "s");
  $("model-line").textContent = `${D.method} model · ${trainingNote} · ${D.source} · ${D.observer}° observer · ${D.generator}`;
  $("ill-buttons").replaceChildren(...ILLS.map((ill, i) => el("button", { type: "button", "data-ill": i }, ill.name)));
  $("finish-buttons").replaceChildren(...FINISHES.map((r, i) =>
    el("button", { type: "button", "data-rough": i, title: "GGX roughness " + r }, D.finishes[i])));
  for (const btn of document.querySelectorAll("#ill-buttons button")) btn.onclick = () => { state.ill = +btn.dataset.ill; update(); };
  for (const btn of document.querySelectorAll("#light-buttons button")) btn.onclick = () => { state.light = btn.dataset.light; update(); };
  for (const btn of document.querySelectorAll("#finish-buttons button")) btn.onclick = () => { state.rough = +btn.dataset.rough; update(); };
  $("angle").oninput = () => { state.angle = Math.round(parseFloat($("angle").value) * 10) / 10; update(); };
  $("angle-value").onchange = () => {
    const v = parseFloat($("angle-value").value);
    if (v >= 0 && v <= 90) { state.angle = v; update(); }
  };
  for (const [key, field] of [["a", "x"], ["b", "x2"]]) {
    const input = $("x-" + key), text = $("x-" + key + "-text");
    input.min = X_LO; input.max = X_HI;
    input.oninput = () => { state[field] = parseFloat(input.value); update(); };
    text.onchange = () => {
      const v = I.compositionInRange(text.value, CTX);
      if (Number.isNaN(v)) { text.classList.add("bad"); return; }
      state[field] = v; text.classList.remove("bad"); text.blur(); update();
    };
    $("ticks-" + key).replaceChildren(...D.training.map((s) => {
      const tick = el("button", { type: "button", class: "tick", "data-x": s.x, title: "measured: " + s.file },
                      (100 * s.x).toFixed(0));
      tick.style.left = (100 * (s.x - X_LO) / (X_HI - X_LO || 1)).toFixed(3) + "%";
      tick.onclick = () => { state[field] = s.x; update(); };
      return tick;
    }));
  }
  $("match-go").onclick = findComposition;
  $("match-target").onkeydown = (e) => { if (e.key === "Enter") findComposition(); };
  const roughNote = FINISHES.length > 1
    ? ` The finishes other than polished are GGX microfacet surfaces (roughness ${FINISHES.slice(1).join(", ")}), tabulated the same way; they change the pictures only.`
    : "";
  const b = (text) => el("b", {}, text);
  $("about").replaceChildren(
    el("p", {}, "Every number and pixel comes from tables the program ", b(D.generator),
       " computed with the same spectral chain as ", el("code", {}, "alloycolor color"), " and ",
       el("code", {}, "alloycolor render"),
       `: n, k of the ${D.method} model → Fresnel reflectance at the angle of incidence (Rs + Rp)/2 → CIE XYZ under the illuminant (${D.observer}° observer) → CIELAB (the illuminant's white) and sRGB (IEC 61966-2-1, no chromatic adaptation). The page interpolates: `,
       b("linearly in the cosine of the angle"), ` (${M} nodes) and `, b("cubically in composition"),
       ` (${T.nodes} nodes, breaks at the measured compositions).`),
    el("p", { id: "table-error", "data-max-de00": T.max_de00, "data-max-srgb8": T.max_srgb8_difference },
       `How far off it can be: against direct spectral evaluation at ${T.check_points.toLocaleString("en")} check points (every node and midpoint in composition × every node and midpoint in angle, all illuminants), the largest error is `,
       b("ΔE00 " + T.max_de00.toPrecision(2)), " and ", b(T.max_srgb8_difference + " in 8-bit sRGB"),
       `. The one-sigma ΔE00 is interpolated linearly between nodes and between the angles ${SIGMA_ANGLES.join(", ")}°.`),
    el("p", {}, "Pictures: each pixel is the table's colour at that pixel's angle of incidence, as the renderer does; in ",
       b("Uniform"), " light that is all (the sphere's centre is the colour at 0°, the rim goes toward white); in ",
       b("Studio"), ` light it is scaled by the brightness of the light tent in the mirror direction (for rough finishes, the tent blurred by the microfacet lobe).${roughNote} Outlines are anti-aliased with the renderer's 4 × 4 coverage.`),
    el("p", {}, `The address holds the view (x = atomic fraction of ${SYS.a}; 18k, 75wt% are accepted too): `,
       el("code", { id: "state-example" })));
  readHash();
  window.addEventListener("hashchange", () => { if (location.hash.replace(/^#/, "") !== stateString()) { readHash(); render(); } });
  render();
  $("state-example").textContent = "#" + stateString();
}
setup();
})();
