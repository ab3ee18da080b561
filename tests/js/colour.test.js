// export/explore/colour.js under Node: the page's colour formulas and table interpolation
// against published values (Sharma, Wu & Dalal 2005; colour-science; IEC 61966-2-1) and
// values worked by hand in the comments.
"use strict";
const test = require("node:test");
const assert = require("node:assert");
const fs = require("node:fs");
const path = require("node:path");
const C = require("../../export/explore/colour.js");

const near = (actual, expected, tolerance, what) =>
  assert.ok(Math.abs(actual - expected) <= tolerance, `${what}: ${actual} vs ${expected} ± ${tolerance}`);

// tests/reference/ciede2000_sharma2005.csv: pair, L1, a1, b1, L2, a2, b2, dE00.
function sharmaPairs() {
  const text = fs.readFileSync(path.join(__dirname, "..", "reference", "ciede2000_sharma2005.csv"), "utf8");
  return text.split("\n").filter((line) => /^[0-9]/.test(line)).map((line) => {
    const v = line.split(",").map(Number);
    return { pair: v[0], lab1: v.slice(1, 4), lab2: v.slice(4, 7), de: v[7] };
  });
}

test("CIEDE2000 gives Sharma, Wu & Dalal's 34 published values to their 4 decimals", () => {
  const pairs = sharmaPairs();
  assert.strictEqual(pairs.length, 34);
  for (const p of pairs) {
    near(C.deltaE00(p.lab1, p.lab2), p.de, 5e-5 + 1e-12, "pair " + p.pair);
    near(C.deltaE00(p.lab2, p.lab1), p.de, 5e-5 + 1e-12, "pair " + p.pair + " reversed");
  }
});

test("CIEDE2000 of a lightness-only step at mid grey is the step", () => {
  // a = b = 0, mean L* = 50: S_L = 1 and the chroma and hue terms vanish.
  near(C.deltaE00([49, 0, 0], [51, 0, 0]), 2, 1e-12, "dL 2");
  assert.strictEqual(C.deltaE00([37, 12, -5], [37, 12, -5]), 0);
});

test("CIELAB matches colour-science and CIE 15:2004", () => {
  // colour.XYZ_to_Lab([0.07049534, 0.10080000, 0.09558313], xy = (0.31270, 0.32900)).
  const white = [0.3127 / 0.329, 1, (1 - 0.3127 - 0.329) / 0.329];
  const lab = C.labFromXYZ([0.07049534, 0.1008, 0.09558313], white);
  near(lab[0], 37.9856291, 1e-7, "L*");
  near(lab[1], -22.61920654, 1e-7, "a*");
  near(lab[2], 4.19811236, 1e-7, "b*");
  const w = C.labFromXYZ(white, white);
  near(w[0], 100, 1e-12, "white L*");
  near(Math.hypot(w[1], w[2]), 0, 1e-12, "white a*, b*");
  // L* = 50 at Y/Yn = (66/116)^3; L* = 8 at the breakpoint (6/29)^3 from both branches;
  // below it L* = (24389/27) Y/Yn.
  near(C.labFromXYZ([1, Math.pow(66 / 116, 3), 1], [1, 1, 1])[0], 50, 1e-12, "L* 50");
  near(C.labFromXYZ([1, 216 / 24389, 1], [1, 1, 1])[0], 8, 1e-12, "breakpoint");
  near(C.labFromXYZ([1, 0.005, 1], [1, 1, 1])[0], (24389 / 27) * 0.005, 1e-12, "linear branch");
});

test("sRGB encoding follows IEC 61966-2-1", () => {
  // 12.92 x 0.0031308 = 0.040449936 at the breakpoint; the power branch meets it there.
  near(C.srgbEncode(0.0031308), 0.040449936, 1e-12, "linear side");
  near(C.srgbEncode(0.0031308 + 1e-12), 0.040449936, 1e-6, "power side");
  near(C.srgbEncode(1), 1, 1e-15, "white");
  // Linear 0.5 is 1.055 x 0.5^(1/2.4) - 0.055 = 0.7354, 8-bit 187.5 -> 188; 0.2140
  // (8-bit 128 decoded: ((128/255 + 0.055)/1.055)^2.4 = 0.21586) encodes back to 128.
  assert.strictEqual(C.srgb8(0.5), 188);
  assert.strictEqual(C.srgb8(0.21586), 128);
  assert.deepStrictEqual([-0.2, 0, 1, 1.7].map(C.srgb8), [0, 0, 255, 255]);
  assert.strictEqual(C.hex([255, 0, 16]), "#ff0010");
  // The matrix is applied row by row.
  assert.deepStrictEqual(C.linearSRGBFromXYZ([[1, 2, 3], [0, 1, 0], [-1, 0, 1]], [1, 10, 100]),
                         [321, 10, 99]);
});

test("atomic and weight fractions of Au-Ag (CIAAW masses) convert both ways", () => {
  const au = 196.96657, ag = 107.8682;
  // 18 karat = 0.75 by weight: (0.75/196.96657) / (0.75/196.96657 + 0.25/107.8682) = 0.62163.
  near(C.atomicFromWeight(0.75, au, ag), 0.621634, 1e-6, "18k");
  // x = 0.5: 196.96657 / (196.96657 + 107.8682) = 0.646142.
  near(C.weightFromAtomic(0.5, au, ag), 0.646142, 1e-6, "x 0.5");
  for (const x of [0, 0.1, 0.5, 0.93, 1]) near(C.atomicFromWeight(C.weightFromAtomic(x, au, ag), au, ag), x, 1e-15, "round trip");
});

// Each segment has its own nodes lo + i (hi - lo) / intervals, i = 0..intervals, numbered
// from seg.first (composition_table.h): nodes 0-4 and 5-10, both ends of the break at 0.2.
const SEGMENTS = [{ lo: 0, hi: 0.2, intervals: 4, first: 0 }, { lo: 0.2, hi: 1, intervals: 5, first: 5 }];
const nodeX = (seg, i) => seg.lo + (i * (seg.hi - seg.lo)) / seg.intervals;
const interpolate = (values, x) => {
  const { first, w } = C.segmentWeights(C.findSegment(SEGMENTS, x), x);
  return w.reduce((sum, wq, q) => sum + wq * values[first + q], 0);
};

test("composition interpolation is exact for cubics, one segment at a time", () => {
  assert.strictEqual(C.findSegment(SEGMENTS, 0.05), SEGMENTS[0]);
  assert.strictEqual(C.findSegment(SEGMENTS, 0.2), SEGMENTS[0]);
  assert.strictEqual(C.findSegment(SEGMENTS, 0.2000001), SEGMENTS[1]);
  // A cubic on the first segment and another on the second (a break at 0.2): 4-point
  // Lagrange interpolation reproduces a cubic exactly.
  const left = (x) => 3 * x * x * x - x + 0.25, right = (x) => -x * x * x + 2 * x * x + 0.5;
  const values = [];
  for (let i = 0; i <= 4; i++) values.push(left(nodeX(SEGMENTS[0], i)));
  for (let i = 0; i <= 5; i++) values.push(right(nodeX(SEGMENTS[1], i)));
  for (let k = 0; k <= 100; k++) {
    const x = k / 100;
    near(interpolate(values, x), x <= 0.2 ? left(x) : right(x), 1e-12, "x " + x);
  }
  // At a node the weights pick that node (x = 0.36 is node 1 of the second segment, the
  // stencil's second point); the four-node stencil stays inside the segment.
  const atNode = C.segmentWeights(SEGMENTS[1], 0.36);
  assert.strictEqual(atNode.first, 5);
  atNode.w.forEach((w, q) => near(w, q === 1 ? 1 : 0, 1e-12, "weight " + q));
  assert.strictEqual(C.segmentWeights(SEGMENTS[1], 0.99).first, 5 + 2);
  assert.strictEqual(C.segmentWeights(SEGMENTS[0], 0.001).first, 0);
});

test("angle interpolation is linear in mu between the table's nodes", () => {
  // Nodes at mu = 0, 0.5, 1 with XYZ (0, 0, 0), (2, 4, 6), (4, 4, 4).
  const row = [0, 0, 0, 2, 4, 6, 4, 4, 4];
  assert.deepStrictEqual(C.xyzAtMu(row, 0.25), [1, 2, 3]);
  assert.deepStrictEqual(C.xyzAtMu(row, 0.75), [3, 4, 5]);
  assert.deepStrictEqual(C.xyzAtMu(row, 1), [4, 4, 4]);
  assert.deepStrictEqual(C.xyzAtMu(row, -3), [0, 0, 0]);
});

test("sigma is linear between composition nodes and between angles", () => {
  // Nodes 0..10 of SEGMENTS, angles 0, 60: sigma = node + angle / 60.
  const angles = [0, 60], sigma = [];
  for (let node = 0; node <= 10; node++) sigma.push(node, node + 1);
  // x = 0.125 is halfway from node 2 (0.1) to node 3 (0.15); 15 deg a quarter of 60.
  near(C.nodeAngleLinear(sigma, SEGMENTS, angles, 0.125, 15), 2.5 + 0.25, 1e-12, "inside");
  // x = 0.28 is halfway from node 5 (0.2) to node 6 (0.36), in the second segment.
  near(C.nodeAngleLinear(sigma, SEGMENTS, angles, 0.28, 0), 5.5, 1e-12, "after the break");
  near(C.nodeAngleLinear(sigma, SEGMENTS, angles, 1, 90), 11, 1e-12, "clamped at the ends");
  near(C.nodeAngleLinear([7, 9], [{ lo: 0, hi: 1, intervals: 1, first: 0 }], [0], 0.5, 40), 8, 1e-12,
       "one angle");
});

test("the inverse of the sRGB matrix gives back the identity", () => {
  // IEC 61966-2-1's XYZ -> linear sRGB matrix.
  const m = [[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]];
  const inv = C.invert3(m);
  for (let i = 0; i < 3; i++) {
    for (let j = 0; j < 3; j++) {
      const v = m[i][0] * inv[0][j] + m[i][1] * inv[1][j] + m[i][2] * inv[2][j];
      near(v, i === j ? 1 : 0, 1e-12, `(M M^-1)[${i}][${j}]`);
    }
  }
});

test("an 8-bit sRGB colour in CIELAB matches colour-science", () => {
  // colour.XYZ_to_Lab(colour.sRGB_to_XYZ([1, 0, 0]), D65 = xy (0.3127, 0.3290)):
  // L* 53.2408, a* 80.0925, b* 67.2032; white gives L* 100, a* = b* = 0.
  const m = [[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]];
  const white = [0.3127 / 0.329, 1, (1 - 0.3127 - 0.329) / 0.329];
  const red = C.labFromSRGB8(m, [255, 0, 0], white);
  near(red[0], 53.2408, 0.02, "L*"); near(red[1], 80.0925, 0.05, "a*"); near(red[2], 67.2032, 0.05, "b*");
  const grey = C.labFromSRGB8(m, [255, 255, 255], white);
  near(grey[0], 100, 0.01, "white L*"); near(grey[1], 0, 0.01, "white a*"); near(grey[2], 0, 0.01, "white b*");
});

test("minimaOf finds every local minimum, best first, and those within the margin only", () => {
  // (x - 0.3)^2 ((x - 0.8)^2 + 0.01): zero at 0.3; a second minimum near 0.778 (d/dx = 0:
  // (x-0.8)^2 + 0.01 + (x-0.3)(x-0.8) = 0, i.e. 2x^2 - 2.7x + 0.89 = 0: its larger root; the
  // smaller, 0.572, is the maximum between).
  const f = (x) => (x - 0.3) ** 2 * ((x - 0.8) ** 2 + 0.01);
  const second = (2.7 + Math.sqrt(2.7 * 2.7 - 8 * 0.89)) / 4;
  const found = C.minimaOf(f, 0, 1, 101, 1);
  assert.strictEqual(found.length, 2);
  near(found[0].x, 0.3, 1e-6, "best");
  near(found[1].x, second, 1e-6, "second");
  assert.strictEqual(C.minimaOf(f, 0, 1, 101, 1e-4).length, 1);
  // A minimum at the end of the range: f decreasing throughout.
  near(C.minimaOf((x) => 1 - x, 0, 1, 11, 1)[0].x, 1, 1e-9, "end");
});

test("windowAround walks out to where g first exceeds the limit, and clips at the range", () => {
  const v = (x0, slope) => (x) => slope * Math.abs(x - x0);
  let w = C.windowAround(v(0.5, 10), 0.5, 1, 0, 1, 5e-4);
  near(w.lo, 0.4, 1e-8, "low"); near(w.hi, 0.6, 1e-8, "high");
  assert.ok(!w.clippedLo && !w.clippedHi);
  w = C.windowAround(v(0.05, 10), 0.05, 1, 0, 1, 5e-4);
  assert.strictEqual(w.lo, 0); assert.ok(w.clippedLo); near(w.hi, 0.15, 1e-8, "high");
  // The first crossing, not the last: g comes back under the limit further out.
  w = C.windowAround((x) => Math.abs(Math.sin(20 * (x - 0.5))), 0.5, 0.5, 0, 1, 5e-4);
  near(w.hi, 0.5 + Math.asin(0.5) / 20, 1e-8, "first crossing");
});
