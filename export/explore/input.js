"use strict";
// What a user types: a composition in the page's text box or address (0.75 as an atomic
// fraction of element a, 75at%, 75wt%, or a karat for gold: 18k, 18kt) and the view kept
// in the address (#x=0.75&x2=0.6&ill=D65&angle=0&light=studio&rough=0).
// Pure functions of the text and of a context
//   ctx = {sys: {a, b, mass_a, mass_b}, x_range: [lo, hi], illuminants: [names],
//          roughness: [GGX alpha per finish]};
// under Node the module exports AlloyInput (tests/js/input.test.js).
// parseComposition follows the library's rules (core/src/composition.cc, ParseComposition)
// to the letter, bound included: the two are tested on one list of inputs
// (tests/reference/composition_inputs.json, tests/composition_parsers_test.cc). Every
// parser here runs in time linear in its input, which it first bounds.
const AlloyInput = (() => {
  const C = typeof AlloyColour !== "undefined" ? AlloyColour : require("./colour.js");
  // The longest composition read (the library's kMaxCompositionChars) and the longest
  // colour target.
  const MAX_COMPOSITION_CHARS = 64;
  const MAX_TARGET_CHARS = 200;
  const MAX_ADDRESS_CHARS = 2000;

  // The library's Trim (space, tab, CR, FF, VT; not a newline) and ASCII lower case.
  const trimBlanks = (s) => s.replace(/^[ \t\r\f\v]+/, "").replace(/[ \t\r\f\v]+$/, "");
  const lowerAscii = (s) => s.replace(/[A-Z]/g, (c) => String.fromCharCode(c.charCodeAt(0) + 32));

  // A whole token as a finite number, as the library reads one (ParseFiniteDouble: an
  // optional sign, digits with an optional point, an optional exponent; "+-1", "1.", ".5"
  // and "1e5" as std::from_chars takes them), or NaN. One pass over the characters.
  function finiteNumber(token) {
    let i = 0;
    const n = token.length;
    const digit = (j) => j < n && token.charCodeAt(j) >= 48 && token.charCodeAt(j) <= 57;
    if (token[i] === "+" || token[i] === "-") {
      if (token[i] === "+" && token[i + 1] === "-") return NaN;
      i++;
    }
    let mantissaDigits = 0, nonzero = false;
    const mantissa = () => { while (digit(i)) { nonzero = nonzero || token[i] !== "0"; i++; mantissaDigits++; } };
    mantissa();
    if (token[i] === ".") { i++; mantissa(); }
    if (mantissaDigits === 0) return NaN;
    if (token[i] === "e" || token[i] === "E") {
      let j = i + 1;
      if (token[j] === "+" || token[j] === "-") j++;
      if (digit(j)) { i = j; while (digit(i)) i++; }
    }
    if (i !== n) return NaN;
    const value = Number(token);
    // Out of range either way (1e400, or 1e-400 read as 0) is refused, as from_chars does.
    return Number.isFinite(value) && (value !== 0 || !nonzero) ? value : NaN;
  }

  // "a", "b" or null: which element is gold.
  const goldSide = (sys) => (sys.a === "Au" ? "a" : sys.b === "Au" ? "b" : null);
  const weight = (x, sys) => C.weightFromAtomic(x, sys.mass_a, sys.mass_b);
  const inUnit = (v, lo, hi) => (v >= lo && v <= hi ? v : NaN);

  // The atomic fraction of element a, or NaN when the library would refuse the text.
  function parseComposition(text, sys) {
    if (typeof text !== "string" && typeof text !== "number") return NaN;
    const raw = String(text);
    if (raw.length > 4 * MAX_COMPOSITION_CHARS) return NaN;  // bounded before any work
    const s = lowerAscii(trimBlanks(raw));
    if (s.length === 0 || s.length > MAX_COMPOSITION_CHARS) return NaN;
    const number = (suffix) => finiteNumber(trimBlanks(s.slice(0, s.length - suffix)));
    if (s.endsWith("at%")) return inUnit(number(3), 0, 100) / 100;
    if (s.endsWith("wt%")) {
      const w = inUnit(number(3), 0, 100) / 100;
      return Number.isNaN(w) ? NaN : C.atomicFromWeight(w, sys.mass_a, sys.mass_b);
    }
    if (s.endsWith("%")) return NaN;  // ambiguous: at% or wt%
    if (s.endsWith("kt") || s.endsWith("k")) {
      const gold = goldSide(sys);
      const k = inUnit(number(s.endsWith("kt") ? 2 : 1), 0, 24);
      if (!gold || Number.isNaN(k)) return NaN;
      const wGold = k / 24;
      return C.atomicFromWeight(gold === "a" ? wGold : 1 - wGold, sys.mass_a, sys.mass_b);
    }
    return inUnit(number(0), 0, 1);
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

  // The view an address gives, over the defaults: {view, bad: [keys whose value was refused]}
  // (bad: ["address"] and the defaults for an address over MAX_ADDRESS_CHARS).
  // ill is an index in ctx.illuminants (any case), rough an index in ctx.roughness.
  function parseAddress(hash, ctx) {
    const view = defaultView(ctx), bad = [];
    const text = String(hash);
    // Bounded before any work: a view's address is under 200 characters.
    if (text.length > MAX_ADDRESS_CHARS) return { view, bad: ["address"] };
    const params = new URLSearchParams(text.replace(/^#/, ""));
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
    const raw = String(text);
    if (raw.length > MAX_TARGET_CHARS) return null;  // bounded before any work
    const t = raw.trim();
    const hexMatch = /^#?([0-9a-fA-F]{6})$/.exec(t);
    if (hexMatch) return { rgb8: [0, 2, 4].map((i) => parseInt(hexMatch[1].slice(i, i + 2), 16)) };
    const parts = t.split(/[\s,;]+/).filter((p) => p !== "");
    if (parts.length !== 3) return null;
    const lab = parts.map(finiteNumber);
    return lab[0] >= 0 && lab[0] <= 100 && lab.every(Number.isFinite) ? { lab } : null;
  }

  return { parseComposition, karat, describeComposition, compositionInRange, defaultView,
           parseAddress, formatAddress, parseColourTarget, finiteNumber, MAX_COMPOSITION_CHARS };
})();
if (typeof module !== "undefined") module.exports = AlloyInput;
