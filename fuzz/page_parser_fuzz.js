// Fuzzes the explorer page's parsers (export/explore/input.js) under Node, as scripts/fuzz.sh
// runs the libFuzzer targets: inputs grown from a dictionary of the forms' pieces and from
// the shared list (tests/reference/composition_inputs.json) by insertion, deletion,
// repetition (runs of thousands of digits) and splicing, each checked for:
//  - no exception, from parseComposition, parseAddress and parseColourTarget;
//  - a composition that is NaN or an atomic fraction in [0, 1];
//  - work linear in the input: the input repeated 256 times may take at most 64 times as
//    long as repeated 16 times, plus 5 ms (a quadratic parser takes 256 times as long);
//  - an accepted composition read again from its own digits gives the same fraction.
//   node fuzz/page_parser_fuzz.js SECONDS ARTIFACT_DIR
// Writes each finding to ARTIFACT_DIR/page-N.json and exits 1 when there was one.
"use strict";
const fs = require("node:fs");
const path = require("node:path");
const I = require("../export/explore/input.js");

const seconds = Number(process.argv[2] || 60);
const artifacts = process.argv[3] || "build-fuzz/artifacts";
const inputs = JSON.parse(fs.readFileSync(path.join(__dirname, "../tests/reference/composition_inputs.json"), "utf8"));
const pieces = ["0", "1", "7", "9", ".", "e", "E", "+", "-", "at%", "wt%", "%", "k", "kt", "karat", " ", "\t", "\n",
                ",", ";", "#", "x=", "&", "=", "\u00b5", "\u00a0", "0x", "inf", "nan", "1e308", "1e-400"];
const systems = [{ a: "Au", b: "Ag", mass_a: 196.96657, mass_b: 107.8682 },
                 { a: "Cu", b: "Zn", mass_a: 63.546, mass_b: 65.38 }];
const ctx = { sys: systems[0], x_range: [0, 1], illuminants: ["A", "D65"], roughness: [0, 0.2] };

// xorshift32: the same run from the same seed.
let state = 0x2545f491;
const random = (n) => {
  state ^= state << 13; state >>>= 0; state ^= state >>> 17; state ^= state << 5; state >>>= 0;
  return state % n;
};
const pick = (list) => list[random(list.length)];

function mutate(text) {
  switch (random(6)) {
    case 0: { const at = random(text.length + 1); return text.slice(0, at) + pick(pieces) + text.slice(at); }
    case 1: { const at = random(text.length + 1); return text.slice(0, at) + text.slice(at + 1 + random(3)); }
    case 2: { const at = random(text.length + 1); return text.slice(0, at) + pick(pieces).repeat(1 + random(3000)) + text.slice(at); }
    case 3: return text + pick(inputs).slice(0, 80);
    case 4: return pick(pieces) + text;
    default: return text.split("").reverse().join("");
  }
}

let found = 0;
function finding(what, input) {
  fs.mkdirSync(artifacts, { recursive: true });
  const file = path.join(artifacts, `page-${found}.json`);
  fs.writeFileSync(file, JSON.stringify({ what, input }));
  console.log(`FUZZ FINDING: ${what} (${file})`);
  found++;
}

const timeOf = (f) => { const t = process.hrtime.bigint(); f(); return Number(process.hrtime.bigint() - t) / 1e6; };

function check(text) {
  for (const sys of systems) {
    let x;
    try { x = I.parseComposition(text, sys); } catch (e) { return finding("parseComposition threw " + e, text); }
    if (!Number.isNaN(x) && !(x >= 0 && x <= 1)) return finding("composition " + x + " outside [0, 1]", text);
    if (!Number.isNaN(x) && /^[0-9.]+$/.test(text) && I.parseComposition(String(x), sys) !== x) {
      return finding("not read back from its digits", text);
    }
  }
  try {
    I.parseAddress("#x=" + encodeURIComponent(text) + "&x2=" + text, ctx);
    I.parseColourTarget(text);
  } catch (e) { return finding("threw " + e, text); }
  if (text.length >= 4 && text.length <= 400) {
    const parsers = [["parseComposition", (t) => I.parseComposition(t, ctx.sys)],
                     ["parseColourTarget", (t) => I.parseColourTarget(t)],
                     ["parseAddress", (t) => I.parseAddress("#x=" + t, ctx)]];
    const text16 = text.repeat(16), text256 = text.repeat(256);
    // The least of three runs: a garbage collection in one is not the parser's.
    const least = (f) => Math.min(timeOf(f), timeOf(f), timeOf(f));
    for (const [name, parse] of parsers) {
      const short = least(() => parse(text16)), long = least(() => parse(text256));
      if (long > 64 * Math.max(short, 0.05) + 5) {
        return finding(`${name}: ${long.toFixed(2)} ms for 256 times the input, ${short.toFixed(2)} ms for 16 times`, text);
      }
    }
  }
}

const end = Date.now() + 1000 * seconds;
let runs = 0;
const corpus = inputs.slice();
while (Date.now() < end && found < 10) {
  let text = pick(corpus);
  for (let m = 1 + random(4); m > 0; m--) text = mutate(text);
  if (text.length > 100000) text = text.slice(0, 100000);
  check(text);
  if (corpus.length < 5000 && random(8) === 0) corpus.push(text);
  runs++;
}
console.log(`page parsers: ${runs} inputs in ${seconds} s, ${found} finding(s)`);
process.exit(found ? 1 : 0);
