"use strict";
// The colour formulas of colorimetry.h (CIE 15:2004 CIELAB, IEC 61966-2-1 sRGB, CIEDE2000
// after Sharma, Wu & Dalal 2005), the composition conversion of composition.h and the
// table interpolation of composition_table.h, in JavaScript. Pure functions, no page state;
// under Node the module exports AlloyColour (tests/js/colour.test.js).
const AlloyColour = (() => {
  const LAB_EPSILON = 216 / 24389;  // (6/29)^3
  const LAB_KAPPA = 24389 / 27;     // (29/3)^3
  const SRGB_LINEAR_MAX = 0.0031308;
  const POW25_7 = 6103515625;       // 25^7
  const rad = (d) => d * (Math.PI / 180);

  const labF = (t) => (t > LAB_EPSILON ? Math.cbrt(t) : (LAB_KAPPA * t + 16) / 116);
  function labFromXYZ(xyz, white) {
    const fx = labF(xyz[0] / white[0]), fy = labF(xyz[1] / white[1]), fz = labF(xyz[2] / white[2]);
    return [116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)];
  }
  // m: the XYZ -> linear sRGB matrix, row by row.
  function linearSRGBFromXYZ(m, xyz) {
    return m.map((row) => row[0] * xyz[0] + row[1] * xyz[1] + row[2] * xyz[2]);
  }
  const srgbEncode = (v) => (v <= SRGB_LINEAR_MAX ? 12.92 * v : 1.055 * Math.pow(v, 1 / 2.4) - 0.055);
  function srgb8(v) {
    const c = v > 0 ? Math.min(v, 1) : 0;
    return Math.round(255 * srgbEncode(c));
  }
  const hex = (rgb8) => "#" + rgb8.map((v) => v.toString(16).padStart(2, "0")).join("");

  function hueDegrees(b, aPrime) {
    if (b === 0 && aPrime === 0) return 0;
    let h = Math.atan2(b, aPrime) * (180 / Math.PI);
    if (h < 0) h += 360;
    return h;
  }
  function deltaE00(lab1, lab2) {
    const c1ab = Math.hypot(lab1[1], lab1[2]), c2ab = Math.hypot(lab2[1], lab2[2]);
    const cab7 = Math.pow(0.5 * (c1ab + c2ab), 7);
    const g = 0.5 * (1 - Math.sqrt(cab7 / (cab7 + POW25_7)));
    const a1 = (1 + g) * lab1[1], a2 = (1 + g) * lab2[1];
    const c1 = Math.hypot(a1, lab1[2]), c2 = Math.hypot(a2, lab2[2]);
    const h1 = hueDegrees(lab1[2], a1), h2 = hueDegrees(lab2[2], a2);
    const achromatic = c1 * c2 === 0;
    const dL = lab2[0] - lab1[0], dC = c2 - c1;
    let dh = 0;
    if (!achromatic) {
      dh = h2 - h1;
      if (dh > 180) dh -= 360;
      else if (dh < -180) dh += 360;
    }
    const dH = 2 * Math.sqrt(c1 * c2) * Math.sin(rad(0.5 * dh));
    const lMean = 0.5 * (lab1[0] + lab2[0]), cMean = 0.5 * (c1 + c2);
    let hMean = h1 + h2;
    if (!achromatic) {
      if (Math.abs(h1 - h2) <= 180) hMean = 0.5 * (h1 + h2);
      else if (h1 + h2 < 360) hMean = 0.5 * (h1 + h2 + 360);
      else hMean = 0.5 * (h1 + h2 - 360);
    }
    const t = 1 - 0.17 * Math.cos(rad(hMean - 30)) + 0.24 * Math.cos(rad(2 * hMean)) +
              0.32 * Math.cos(rad(3 * hMean + 6)) - 0.20 * Math.cos(rad(4 * hMean - 63));
    const dTheta = 30 * Math.exp(-((hMean - 275) / 25) * ((hMean - 275) / 25));
    const c7 = Math.pow(cMean, 7);
    const rC = 2 * Math.sqrt(c7 / (c7 + POW25_7));
    const l50 = (lMean - 50) * (lMean - 50);
    const sL = 1 + 0.015 * l50 / Math.sqrt(20 + l50);
    const sC = 1 + 0.045 * cMean;
    const sH = 1 + 0.015 * cMean * t;
    const rT = -Math.sin(rad(2 * dTheta)) * rC;
    const l = dL / sL, c = dC / sC, h = dH / sH;
    return Math.sqrt(l * l + c * c + h * h + rT * c * h);
  }

  // x_atomic <-> weight fraction of element a, atomic masses ma, mb.
  function weightFromAtomic(x, ma, mb) { const a = x * ma, b = (1 - x) * mb; return a / (a + b); }
  function atomicFromWeight(w, ma, mb) { const a = w / ma, b = (1 - w) / mb; return a / (a + b); }

  // 4-point Lagrange weights in a segment {lo, hi, intervals, first} at x: node index and
  // weights, as composition_table.cc.
  function segmentWeights(seg, x) {
    const step = (seg.hi - seg.lo) / seg.intervals;
    const u = Math.min(Math.max((x - seg.lo) / step, 0), seg.intervals);
    const cell = Math.min(Math.floor(u), seg.intervals - 1);
    const first = Math.min(Math.max(cell - 1, 0), seg.intervals - 3);
    const t = u - first;
    return { first: seg.first + first, w: [-(t - 1) * (t - 2) * (t - 3) / 6, t * (t - 2) * (t - 3) / 2,
                                           -t * (t - 1) * (t - 3) / 2, t * (t - 1) * (t - 2) / 6] };
  }
  function findSegment(segments, x) {
    let s = 0;
    while (s + 1 < segments.length && x > segments[s].hi) s++;
    return segments[s];
  }
  // The table's row at composition x: the nodes' rows (src[node * rowLength + i]) weighted
  // by segmentWeights, as the page shades from them.
  function rowAtX(segments, src, rowLength, x) {
    const { first, w } = segmentWeights(findSegment(segments, x), x);
    const out = new Float64Array(rowLength);
    for (let q = 0; q < 4; q++) {
      const base = (first + q) * rowLength, wq = w[q];
      for (let i = 0; i < rowLength; i++) out[i] += wq * src[base + i];
    }
    return out;
  }
  // XYZ at mu = cos(angle) from a row of XYZ triples on mu = 0, 1/(m-1), ..., 1: linear.
  function xyzAtMu(row, mu) {
    const m = row.length / 3, t = Math.min(Math.max(mu, 0), 1) * (m - 1);
    const i = Math.min(Math.floor(t), m - 2), f = t - i, a = 3 * i;
    return [row[a] + f * (row[a + 3] - row[a]), row[a + 1] + f * (row[a + 4] - row[a + 1]),
            row[a + 2] + f * (row[a + 5] - row[a + 2])];
  }
  // A value tabulated per composition node and angle (sigma[node * angles.length + a]):
  // linear in x between nodes and in angle between the angles.
  function nodeAngleLinear(sigma, segments, anglesDeg, x, angleDeg) {
    const seg = findSegment(segments, x), step = (seg.hi - seg.lo) / seg.intervals;
    const u = Math.min(Math.max((x - seg.lo) / step, 0), seg.intervals);
    const i = Math.min(Math.floor(u), seg.intervals - 1), f = u - i, node = seg.first + i;
    const na = anglesDeg.length;
    let a = 0;
    while (a + 2 < na && angleDeg > anglesDeg[a + 1]) a++;
    const g = na > 1 ? Math.min(Math.max((angleDeg - anglesDeg[a]) / (anglesDeg[a + 1] - anglesDeg[a]), 0), 1) : 0;
    const at = (nd) => (na > 1 ? sigma[nd * na + a] * (1 - g) + sigma[nd * na + a + 1] * g : sigma[nd * na]);
    return at(node) * (1 - f) + at(node + 1) * f;
  }
  // ---- From colour to composition (color/match.h, on the page's tables).
  // The inverse of a 3 x 3 matrix given row by row (the cofactors over the determinant).
  function invert3(m) {
    const [a, b, c] = m, det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                              a[2] * (b[0] * c[1] - b[1] * c[0]);
    return [[(b[1] * c[2] - b[2] * c[1]) / det, (a[2] * c[1] - a[1] * c[2]) / det, (a[1] * b[2] - a[2] * b[1]) / det],
            [(b[2] * c[0] - b[0] * c[2]) / det, (a[0] * c[2] - a[2] * c[0]) / det, (a[2] * b[0] - a[0] * b[2]) / det],
            [(b[0] * c[1] - b[1] * c[0]) / det, (a[1] * c[0] - a[0] * c[1]) / det, (a[0] * b[1] - a[1] * b[0]) / det]];
  }
  const srgbDecode = (v) => (v <= 0.04045 ? v / 12.92 : Math.pow((v + 0.055) / 1.055, 2.4));
  // CIELAB of an 8-bit sRGB colour (no chromatic adaptation, as the page shows colours)
  // against the illuminant's white, as LabFromHex; m: the XYZ -> linear sRGB matrix.
  function labFromSRGB8(m, rgb8, white) {
    const linear = rgb8.map((v) => srgbDecode(v / 255));
    return labFromXYZ(linearSRGBFromXYZ(invert3(m), linear), white);
  }

  // Golden-section search for the minimum of f on [a, b] (f unimodal there), to `tol`.
  function goldenMinimum(f, a, b, tol) {
    const r = (Math.sqrt(5) - 1) / 2;
    let c = b - r * (b - a), d = a + r * (b - a), fc = f(c), fd = f(d);
    while (b - a > tol) {
      if (fc <= fd) { b = d; d = c; fd = fc; c = b - r * (b - a); fc = f(c); }
      else { a = c; c = d; fc = fd; d = a + r * (b - a); fd = f(d); }
    }
    const x = 0.5 * (a + b), fx = f(x);
    return fx <= Math.min(fc, fd) ? { x, value: fx } : (fc <= fd ? { x: c, value: fc } : { x: d, value: fd });
  }
  // The local minima of f over [lo, hi], as color::Match finds them: f at n evenly spaced
  // points, every local minimum of the scan (ends included) refined inside its two
  // neighbouring intervals; those within `margin` of the best, best first.
  function minimaOf(f, lo, hi, n, margin) {
    const xs = [], fs = [];
    for (let i = 0; i < n; i++) { xs.push(lo + (hi - lo) * i / (n - 1)); fs.push(f(xs[i])); }
    const found = [];
    for (let i = 0; i < n; i++) {
      if ((i > 0 && fs[i - 1] < fs[i]) || (i + 1 < n && fs[i + 1] < fs[i])) continue;
      if (i > 0 && fs[i - 1] === fs[i]) continue;  // a flat run: its first point only
      const m = goldenMinimum(f, xs[Math.max(i - 1, 0)], xs[Math.min(i + 1, n - 1)], 1e-9 * (hi - lo || 1));
      found.push(m.value <= fs[i] ? m : { x: xs[i], value: fs[i] });
    }
    found.sort((p, q) => p.value - q.value);
    return found.filter((m) => m.value <= found[0].value + margin);
  }
  // The largest interval around x0 inside [lo, hi] where g(x) <= limit (g(x0) = 0, g
  // continuous): walked out in steps of `step` and bisected at the first step that leaves
  // it, as color::Tolerance. clippedLo / clippedHi: the window reaches the range's end.
  function windowAround(g, x0, limit, lo, hi, step) {
    const edge = (dir, end) => {
      let inside = x0;
      for (;;) {
        const next = dir > 0 ? Math.min(inside + step, end) : Math.max(inside - step, end);
        if (g(next) > limit) {
          let a = inside, b = next;
          while (Math.abs(b - a) > 1e-9) { const mid = 0.5 * (a + b); if (g(mid) > limit) b = mid; else a = mid; }
          return { x: a, clipped: false };
        }
        if (next === end) return { x: end, clipped: true };
        inside = next;
      }
    };
    const l = edge(-1, lo), h = edge(1, hi);
    return { lo: l.x, hi: h.x, clippedLo: l.clipped, clippedHi: h.clipped };
  }

  return { labFromXYZ, linearSRGBFromXYZ, srgbEncode, srgb8, hex, deltaE00, weightFromAtomic,
           atomicFromWeight, segmentWeights, findSegment, rowAtX, xyzAtMu, nodeAngleLinear, invert3,
           labFromSRGB8, minimaOf, windowAround };
})();
if (typeof module !== "undefined") module.exports = AlloyColour;
