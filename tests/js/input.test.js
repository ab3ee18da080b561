// export/explore/input.js under Node: compositions typed in the page and the view kept in its
// address. Expected compositions are worked by hand from CIAAW atomic masses.
"use strict";
const test = require("node:test");
const assert = require("node:assert");
const I = require("../../export/explore/input.js");

const AU_AG = { a: "Au", b: "Ag", mass_a: 196.96657, mass_b: 107.8682 };
const AG_AU = { a: "Ag", b: "Au", mass_a: 107.8682, mass_b: 196.96657 };
const CU_ZN = { a: "Cu", b: "Zn", mass_a: 63.546, mass_b: 65.38 };
// 18k: (0.75/196.96657) / (0.75/196.96657 + 0.25/107.8682) = 0.0038078 / 0.0061254.
const X_18K = 0.621634;
// 14k (w = 14/24): (0.58333/196.96657) / (0.58333/196.96657 + 0.41667/107.8682)
// = 0.0029616 / 0.0068243.
const X_14K = 0.433975;
const CTX = { sys: AU_AG, x_range: [0, 1], illuminants: ["A", "D50", "D65"], roughness: [0, 0.2] };

const near = (actual, expected, tolerance, what) =>
  assert.ok(Math.abs(actual - expected) <= tolerance, `${what}: ${actual} vs ${expected} ± ${tolerance}`);

test("compositions: fraction, at%, wt% and karat", () => {
  for (const [text, x] of [["0.75", 0.75], [".5", 0.5], ["75at%", 0.75], ["75 at%", 0.75], [" 7.5AT% ", 0.075],
                           ["1", 1], ["0", 0], ["+0.5", 0.5], ["5e-1", 0.5], ["1.", 1]]) {
    near(I.parseComposition(text, AU_AG), x, 1e-15, text);
  }
  near(I.parseComposition("75wt%", AU_AG), X_18K, 1e-6, "75wt%");
  for (const text of ["18k", "18K", "18 kt", "\t18kt"]) near(I.parseComposition(text, AU_AG), X_18K, 1e-6, text);
  // With gold as element b the karat is 1 - w of element a.
  near(I.parseComposition("18k", AG_AU), 1 - X_18K, 1e-6, "18k, gold as b");
  assert.ok(Number.isNaN(I.parseComposition("18k", CU_ZN)), "karat without gold");
});

// As the library (core/src/composition.cc) refuses them; tests/composition_parsers_test.cc
// checks the two against each other on tests/reference/composition_inputs.json.
test("compositions: anything else is refused", () => {
  for (const text of ["", "abc", "-0.5", "0.5.5", "50 % Au", "18kk", "0x10", "<img src=x onerror=alert(1)>",
                      "0.5;alert(1)", null, undefined, "75%", "18karat", "0.5\n", "+-0.5", "1e400", "1e-400",
                      "25k", "101at%", "75", "0,75", "7 5at%"]) {
    assert.ok(Number.isNaN(I.parseComposition(text, AU_AG)), JSON.stringify(text));
  }
  // In range only, and clamped into it within rounding.
  const ctx = { ...CTX, x_range: [0.2, 0.8] };
  assert.ok(Number.isNaN(I.compositionInRange("0.9", ctx)));
  assert.strictEqual(I.compositionInRange("0.8000000001", ctx), 0.8);
  assert.strictEqual(I.compositionInRange("50at%", ctx), 0.5);
});

// The length is bounded (the library's 64 characters) before any parsing: a valid number
// written longer is refused, and so is a run of 30,000 digits in the address or the
// colour box (a link that froze the page for seconds when the parser was quadratic).
test("inputs are bounded in length", () => {
  const long = "0." + "0".repeat(I.MAX_COMPOSITION_CHARS) + "5";
  assert.ok(Number.isNaN(I.parseComposition(long, AU_AG)));
  near(I.parseComposition("0." + "0".repeat(I.MAX_COMPOSITION_CHARS - 3) + "5", AU_AG), 0, 1e-60, "64 characters");
  const digits = "1".repeat(30000);
  for (const text of [digits, digits + "k", digits + "x", "." + digits + "at%"]) {
    assert.ok(Number.isNaN(I.parseComposition(text, AU_AG)), text.slice(-4));
  }
  assert.deepStrictEqual(I.parseAddress("#x=" + digits.slice(0, 1000) + "k", CTX).bad, ["x"]);
  assert.deepStrictEqual(I.parseAddress("#x=" + digits + "k", CTX).bad, ["address"]);
  assert.strictEqual(I.parseColourTarget(digits + "," + digits + "," + digits), null);
});

test("a composition is described by karat for gold, else by at%", () => {
  assert.deepStrictEqual(I.describeComposition(X_18K, AU_AG), { main: "18.0 k", rest: "62.2 at% Au · 75.0 wt% Au" });
  // Cu-Zn 70/30 at%: w = 0.7 x 63.546 / (0.7 x 63.546 + 0.3 x 65.38) = 44.482 / 64.096 = 0.694.
  assert.deepStrictEqual(I.describeComposition(0.7, CU_ZN), { main: "70.0 at% Cu", rest: "69.4 wt% Cu" });
  near(I.karat(1, AU_AG), 24, 1e-12, "pure gold");
  assert.strictEqual(I.karat(0.5, CU_ZN), null);
});

test("an empty address gives the default view", () => {
  const { view, bad } = I.parseAddress("", CTX);
  assert.deepStrictEqual(bad, []);
  near(view.x, X_18K, 1e-6, "x is 18k");
  near(view.x2, X_14K, 1e-6, "x2 is 14k");
  assert.deepStrictEqual({ ...view, x: 0, x2: 0 }, { x: 0, x2: 0, ill: 2, angle: 0, light: "studio", rough: 0 });
  // Without gold: 3/4 and 1/2 of the range; without D65 the first illuminant.
  const cuZn = I.parseAddress("", { sys: CU_ZN, x_range: [0.6, 1], illuminants: ["A"], roughness: [0] }).view;
  near(cuZn.x, 0.9, 1e-15, "x");
  near(cuZn.x2, 0.8, 1e-15, "x2");
  assert.strictEqual(cuZn.ill, 0);
});

test("an address sets the view, and refuses what it cannot use key by key", () => {
  const { view, bad } = I.parseAddress("#x=0.3&x2=18k&ill=d50&angle=45.5&light=uniform&rough=0.2", CTX);
  assert.deepStrictEqual(bad, []);
  assert.strictEqual(view.x, 0.3);
  near(view.x2, X_18K, 1e-6, "x2");
  assert.deepStrictEqual([view.ill, view.angle, view.light, view.rough], [1, 45.5, "uniform", 1]);
  const refused = I.parseAddress("x=1.5&x2=%3Cimg%20src%3Dx%3E&ill=X9&angle=91&light=dark&rough=0.3", CTX);
  assert.deepStrictEqual(refused.bad, ["x", "x2", "ill", "angle", "light", "rough"]);
  assert.deepStrictEqual(refused.view, I.defaultView(CTX));
  assert.deepStrictEqual(I.parseAddress("#angle=-1&unknown=1", CTX).bad, ["angle"]);
});

test("the address of a view reads back as that view", () => {
  const view = { x: 0.123456789, x2: 0.5, ill: 0, angle: 30, light: "uniform", rough: 1 };
  const text = I.formatAddress(view, CTX);
  assert.strictEqual(text, "x=0.123457&x2=0.5&ill=A&angle=30&light=uniform&rough=0.2");
  const back = I.parseAddress("#" + text, CTX);
  assert.deepStrictEqual(back.bad, []);
  assert.deepStrictEqual(back.view, { ...view, x: 0.123457 });
});

test("a target colour is #rrggbb or three CIELAB numbers, nothing else", () => {
  assert.deepStrictEqual(I.parseColourTarget(" #C8a46e "), { rgb8: [200, 164, 110] });
  assert.deepStrictEqual(I.parseColourTarget("c8a46e"), { rgb8: [200, 164, 110] });
  assert.deepStrictEqual(I.parseColourTarget("80, 5.5, -3e1"), { lab: [80, 5.5, -30] });
  assert.deepStrictEqual(I.parseColourTarget("80 5 30"), { lab: [80, 5, 30] });
  for (const bad of ["", "#c8a46", "#c8a46e0", "#zzzzzz", "80, 5", "80, 5, 30, 1", "120, 0, 0", "-1, 0, 0",
                     "80, five, 30", "80,,5", "NaN, 0, 0", "<b>80</b>, 0, 0"]) {
    assert.strictEqual(I.parseColourTarget(bad), null, JSON.stringify(bad));
  }
});
