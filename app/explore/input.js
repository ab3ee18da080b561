"use strict";
// What a user types: a composition in the page's text box or address (0.75 as an atomic
// fraction of element a, 75%, 75at%, 75wt%, or a karat for gold: 18k, 18kt, 18karat) and
// the view kept in the address (#x=0.75&x2=0.6&ill=D65&angle=0&light=studio&rough=0).
// Pure functions of the text and of a context
//   ctx = {sys: {a, b, mass_a, mass_b}, x_range: [lo, hi], illuminants: [names],
//          roughness: [GGX alpha per finish]};
// under Node the module exports AlloyInput (tests/js/input.test.js).
const AlloyInput = (() => {
  const C = typeof AlloyColour !== "undefined" ? AlloyColour : require("./colour.js");
  const NUMBER = "([0-9]*\\.?[0-9]+)";
  const KARAT = new RegExp("^" + NUMBER + "(k|kt|karat)$");
  const WEIGHT = new RegExp("^" + NUMBER + "wt%$");
  const ATOMIC = new RegExp("^" + NUMBER + "(at)?%$");
  const FRACTION = new RegExp("^" + NUMBER + "$");

  // "a", "b" or null: which element is gold.
  const goldSide = (sys) => (sys.a === "Au" ? "a" : sys.b === "Au" ? "b" : null);
  const weight = (x, sys) => C.weightFromAtomic(x, sys.mass_a, sys.mass_b);

  // The atomic fraction of element a, or NaN when the text is none of the forms.
  function parseComposition(text, sys) {
    const s = String(text).trim().toLowerCase().replace(/\s+/g, "");
    let m;
    if ((m = s.match(KARAT))) {
      const gold = goldSide(sys);
      if (!gold) return NaN;
      const wGold = parseFloat(m[1]) / 24;
      return C.atomicFromWeight(gold === "a" ? wGold : 1 - wGold, sys.mass_a, sys.mass_b);
    }
    if ((m = s.match(WEIGHT))) return C.atomicFromWeight(parseFloat(m[1]) / 100, sys.mass_a, sys.mass_b);
    if ((m = s.match(ATOMIC))) return parseFloat(m[1]) / 100;
    if ((m = s.match(FRACTION))) return parseFloat(m[1]);
    return NaN;
  }

  // Karat of x, or null without gold.
  function karat(x, sys) {
    const gold = goldSide(sys);
    return gold === "a" ? 24 * weight(x, sys) : gold === "b" ? 24 * (1 - weight(x, sys)) : null;
  }

  // x as the page shows it: main (karat for gold, else at%) and the rest.
  function describeComposition(x, sys) {
    const at = (100 * x).toFixed(1) + " at% " + sys.a;
    const wt = (100 * weight(x, sys)).toFixed(1) + " wt% " + sys.a;
    const k = karat(x, sys);
    return k !== null ? { main: k.toFixed(1) + " k", rest: at + " · " + wt } : { main: at, rest: wt };
  }

  const inRange = (x, ctx) => x >= ctx.x_range[0] - 1e-9 && x <= ctx.x_range[1] + 1e-9;
  const clampX = (x, ctx) => Math.min(Math.max(x, ctx.x_range[0]), ctx.x_range[1]);

  // A composition the page accepts (in the model's range, clamped to it), or NaN.
  function compositionInRange(text, ctx) {
    const x = parseComposition(text, ctx.sys);
    return Number.isFinite(x) && inRange(x, ctx) ? clampX(x, ctx) : NaN;
  }

  // The view without an address: 18k and 14k for gold (else 3/4 and 1/2 of the range),
  // D65 when offered, normal incidence, studio light, polished.
  function defaultView(ctx) {
    const [lo, hi] = ctx.x_range;
    const k18 = compositionInRange("18k", ctx), k14 = compositionInRange("14k", ctx);
    const d65 = ctx.illuminants.indexOf("D65");
    return {
      x: Number.isNaN(k18) ? lo + 0.75 * (hi - lo) : k18,
      x2: Number.isNaN(k14) ? lo + 0.5 * (hi - lo) : k14,
      ill: d65 >= 0 ? d65 : 0, angle: 0, light: "studio", rough: 0,
    };
  }

  // The view an address gives, over the defaults: {view, bad: [keys whose value was refused]}.
  // ill is an index in ctx.illuminants (any case), rough an index in ctx.roughness.
  function parseAddress(hash, ctx) {
    const view = defaultView(ctx), bad = [];
    const params = new URLSearchParams(String(hash).replace(/^#/, ""));
    for (const key of ["x", "x2"]) {
      if (!params.has(key)) continue;
      const x = compositionInRange(params.get(key), ctx);
      if (Number.isNaN(x)) bad.push(key); else view[key] = x;
    }
    if (params.has("ill")) {
      const name = params.get("ill").toLowerCase();
      const i = ctx.illuminants.findIndex((ill) => ill.toLowerCase() === name);
      if (i >= 0) view.ill = i; else bad.push("ill");
    }
    if (params.has("angle")) {
      const a = parseFloat(params.get("angle"));
      if (a >= 0 && a <= 90) view.angle = a; else bad.push("angle");
    }
    if (params.has("light")) {
      const l = params.get("light");
      if (l === "studio" || l === "uniform") view.light = l; else bad.push("light");
    }
    if (params.has("rough")) {
      const r = ctx.roughness.findIndex((v) => Math.abs(v - parseFloat(params.get("rough"))) < 1e-9);
      if (r >= 0) view.rough = r; else bad.push("rough");
    }
    return { view, bad };
  }

  // The address of a view, without "#" (compositions to 6 decimals).
  function formatAddress(view, ctx) {
    const fmtX = (x) => String(Math.round(x * 1e6) / 1e6);
    return "x=" + fmtX(view.x) + "&x2=" + fmtX(view.x2) + "&ill=" + ctx.illuminants[view.ill] +
           "&angle=" + view.angle + "&light=" + view.light + "&rough=" + ctx.roughness[view.rough];
  }

  // A target colour as typed in the page's match box: 8-bit sRGB as "#rrggbb" (or
  // "rrggbb"), or CIELAB as three numbers "L*, a*, b*" (commas or spaces; L* in 0-100).
  // Returns { rgb8 } or { lab }, or null for anything else.
  function parseColourTarget(text) {
    const t = String(text).trim();
    const hexMatch = /^#?([0-9a-fA-F]{6})$/.exec(t);
    if (hexMatch) return { rgb8: [0, 2, 4].map((i) => parseInt(hexMatch[1].slice(i, i + 2), 16)) };
    const parts = t.split(/[\s,;]+/).filter((p) => p !== "");
    if (parts.length !== 3 || !parts.every((p) => /^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/.test(p))) return null;
    const lab = parts.map(Number);
    return lab[0] >= 0 && lab[0] <= 100 && lab.every(Number.isFinite) ? { lab } : null;
  }

  return { parseComposition, karat, describeComposition, compositionInRange, defaultView,
           parseAddress, formatAddress, parseColourTarget };
})();
if (typeof module !== "undefined") module.exports = AlloyInput;
