// The explorer page's colour-to-composition box and tolerance window against the program's
// own `match` and `tolerance` (color/match.cc, an independent implementation in C++): the
// page's functions (colour.js, input.js) on the tables of a page the program wrote.
// Needs the program (ALLOYCOLOR_BINARY, set by ctest); skipped (77) without it.
"use strict";
const test = require("node:test");
const assert = require("node:assert");
const fs = require("node:fs");
const os = require("node:os");
const path = require("node:path");
const { execFileSync } = require("node:child_process");
const C = require("../../export/explore/colour.js");
const I = require("../../export/explore/input.js");

const program = process.env.ALLOYCOLOR_BINARY;
if (!program || !fs.existsSync(program)) {
  console.log("ALLOYCOLOR_BINARY is not set to the program: skipped");
  process.exit(77);
}
const run = (...args) => execFileSync(program, args, { encoding: "utf8", stdio: ["ignore", "pipe", "pipe"] });
const near = (actual, expected, tolerance, what) =>
  assert.ok(Math.abs(actual - expected) <= tolerance, `${what}: ${actual} vs ${expected} ± ${tolerance}`);

// A model (eps-linear: quick to fit) and the page the program writes for it.
const dir = fs.mkdtempSync(path.join(os.tmpdir(), "alloycolor-match-"));
const model = path.join(dir, "m.json");
run("fit", "--data", "Au-Ag", "--method", "eps-linear", "--out", model, "--quiet");
run("explore", "--model", model, "--out", path.join(dir, "page.html"), "--quiet");
const html = fs.readFileSync(path.join(dir, "page.html"), "utf8");
const D = JSON.parse(/<script type="application\/json" id="explorer-data">([\s\S]*?)<\/script>/.exec(html)[1]);
const T = D.table;
const f32 = (b64) => { const b = Buffer.from(b64, "base64"); return new Float32Array(b.buffer, b.byteOffset, b.length >> 2); };
const segments = T.segments.map((s) => ({ lo: s[0], hi: s[1], intervals: s[2], first: s[3] }));
const d65 = T.illuminants.find((ill) => ill.name === "D65");
const xyz = f32(d65.xyz[0]);
const [xLo, xHi] = D.x_range;
// The page's colour at normal incidence under D65 (app.js labAt with angle 0).
const labAt = (x) => C.labFromXYZ(C.xyzAtMu(C.rowAtX(segments, xyz, 3 * T.mu_nodes, x), 1), d65.white);
const pageMatch = (lab) => C.minimaOf((x) => C.deltaE00(lab, labAt(x)), xLo, xHi, 1001, 1);

test("a colour of the model's own gives back its composition, as 'alloycolor match --lab' does", () => {
  for (const x of [0.12, 0.37, 0.75]) {
    const lab = JSON.parse(run("color", "--model", model, "--x", String(x), "--json")).Lab;
    const page = pageMatch(lab)[0];
    const cli = JSON.parse(run("match", "--model", model, "--lab", lab.join(","), "--json")).matches[0];
    near(page.x, x, 1e-4, `page at x = ${x}`);
    near(page.x, cli.x_atomic, 1e-4, `page against match at x = ${x}`);
    assert.ok(page.value < 0.05, `dE00 left ${page.value}`);
  }
});

test("a hex colour is read as the program reads --hex, reachable or not", () => {
  const srgb8 = JSON.parse(run("color", "--model", model, "--x", "0.45", "--json")).srgb8;
  const reachable = "#" + srgb8.map((v) => v.toString(16).padStart(2, "0")).join("");
  for (const hex of [reachable, "#c8a46e", "#2040c0"]) {
    const target = I.parseColourTarget(hex);
    const page = pageMatch(C.labFromSRGB8(D.srgb_matrix, target.rgb8, d65.white))[0];
    const cli = JSON.parse(run("match", "--model", model, "--hex", hex, "--json"));
    near(page.x, cli.matches[0].x_atomic, 1e-4, hex + ": composition");
    near(page.value, cli.matches[0].de00, 0.01, hex + ": dE00 left");
    assert.strictEqual(page.value <= 1, cli.reachable, hex + ": reachable");
  }
});

test("the window on slider A is 'alloycolor tolerance --de 1' at the page's angle and light", () => {
  for (const x of [0.2, 0.6, 0.97]) {
    const lab0 = labAt(x);
    const w = C.windowAround((v) => C.deltaE00(lab0, labAt(v)), x, 1, xLo, xHi, 5e-4);
    const cli = JSON.parse(run("tolerance", "--model", model, "--x", String(x), "--de", "1", "--angles", "0",
                               "--illuminants", "D65", "--json"));
    near(w.lo, cli.x_low, 1e-4, `x = ${x}: low end`);
    near(w.hi, cli.x_high, 1e-4, `x = ${x}: high end`);
    assert.strictEqual(w.clippedLo, cli.clipped_low, `x = ${x}: clipped low`);
    assert.strictEqual(w.clippedHi, cli.clipped_high, `x = ${x}: clipped high`);
  }
});

test.after(() => fs.rmSync(dir, { recursive: true, force: true }));
