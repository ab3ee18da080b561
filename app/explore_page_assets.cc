// The explorer page's HTML, CSS and JavaScript (see explore_page.h). Kept as plain text
// so that it reads as the page it is; ExplorePageHtml puts the parts together with the
// data block.
#include "explore_page.h"

namespace alloycolor::app {

const char kExploreHtmlHead[] = R"HTML(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>@TITLE@</title>
)HTML";

const char kExploreCss[] = R"CSS(
:root {
  --bg: #16171a; --panel: #1f2125; --panel2: #26292e; --line: #353840;
  --text: #ebe8e1; --muted: #9d9a92; --faint: #6d6b66; --accent: #d9b56c;
}
* { box-sizing: border-box; }
html { background: var(--bg); }
body { margin: 0; color: var(--text); background: var(--bg);
  font: 14px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", sans-serif; }
.wrap { max-width: 1120px; margin: 0 auto; padding: 18px 20px 40px; }
header { display: flex; align-items: baseline; gap: 16px; flex-wrap: wrap;
  border-bottom: 1px solid var(--line); padding-bottom: 12px; }
header h1 { font-size: 21px; font-weight: 600; margin: 0; letter-spacing: 0.01em; }
header h1 .sys { color: var(--accent); }
header .model { color: var(--muted); }
.toolbar { display: flex; flex-wrap: wrap; gap: 18px 26px; align-items: center;
  padding: 14px 0; border-bottom: 1px solid var(--line); }
.toolbar .group { display: flex; align-items: center; gap: 8px; }
.toolbar .label { color: var(--muted); font-size: 12px; text-transform: uppercase;
  letter-spacing: 0.08em; }
.seg { display: inline-flex; border: 1px solid var(--line); border-radius: 7px; overflow: hidden; }
.seg button { background: transparent; color: var(--text); border: 0; padding: 5px 11px;
  font: inherit; cursor: pointer; border-right: 1px solid var(--line); }
.seg button:last-child { border-right: 0; }
.seg button:hover { background: var(--panel2); }
.seg button[aria-pressed="true"] { background: var(--accent); color: #1b1a17; font-weight: 600; }
input[type=range] { accent-color: var(--accent); }
#angle { width: 150px; }
#angle-value { width: 66px; }
input[type=number], input[type=text] { background: var(--panel2); color: var(--text);
  border: 1px solid var(--line); border-radius: 6px; padding: 4px 7px; font: inherit; }
input.bad { border-color: #c0504d; }
.metal { display: grid; grid-template-columns: auto 1fr; gap: 0 22px; padding: 18px 0 6px; }
.metal .slider { grid-column: 1 / 3; display: grid; grid-template-columns: 34px 1fr 150px;
  gap: 12px; align-items: center; margin-bottom: 10px; }
.tag { display: inline-flex; width: 30px; height: 30px; border-radius: 50%;
  align-items: center; justify-content: center; font-weight: 700; color: #1b1a17;
  background: var(--accent); }
.track { position: relative; padding-bottom: 30px; }
.track input[type=range] { width: 100%; margin: 0; }
.ticks { position: absolute; left: 8px; right: 8px; top: 22px; height: 26px; }
.tick { position: absolute; transform: translateX(-50%); font-size: 11px; color: var(--muted);
  cursor: pointer; white-space: nowrap; background: none; border: 0; padding: 0; font-family: inherit; }
.tick::before { content: ""; display: block; width: 2px; height: 7px; margin: 0 auto 2px;
  background: var(--accent); border-radius: 1px; }
.tick:hover { color: var(--text); }
.readout { grid-column: 2 / 4; margin-top: -22px; font-size: 13px; color: var(--muted); }
.readout b { color: var(--text); font-size: 15px; font-weight: 600; }
.stage { display: flex; gap: 4px; border-radius: 12px; overflow: hidden;
  background: radial-gradient(ellipse at 50% 38%, #5b5d62 0%, #34363b 58%, #232428 100%); }
.stage.uniform { background: radial-gradient(ellipse at 50% 38%, #4a4c50 0%, #2c2e32 70%); }
.stage canvas { display: block; }
.card { background: var(--panel); border: 1px solid var(--line); border-radius: 12px;
  padding: 14px 16px; display: grid; grid-template-columns: 96px 1fr; gap: 12px 16px;
  align-content: start; }
.swatch { width: 96px; height: 96px; border-radius: 9px; border: 1px solid #0006;
  box-shadow: inset 0 0 0 1px #ffffff14; }
.hexline { align-self: center; }
.hexline .hex { font: 600 22px/1.1 ui-monospace, "DejaVu Sans Mono", Menlo, monospace; }
.hexline .cond { color: var(--muted); font-size: 12px; margin-top: 6px; }
dl.values { grid-column: 1 / 3; display: grid; grid-template-columns: 118px 1fr; gap: 5px 10px; margin: 0; }
dl.values dt { color: var(--muted); }
dl.values dd { margin: 0; font-family: ui-monospace, "DejaVu Sans Mono", Menlo, monospace; font-size: 13px; }
.difference { margin: 8px 0 0; padding: 14px 18px; border-radius: 12px; background: var(--panel);
  border: 1px solid var(--line); display: flex; align-items: center; gap: 18px; flex-wrap: wrap; }
.difference .pair { display: flex; }
.difference .pair span { width: 46px; height: 46px; display: block; }
.difference .pair span:first-child { border-radius: 8px 0 0 8px; }
.difference .pair span:last-child { border-radius: 0 8px 8px 0; }
.difference .de { font-size: 26px; font-weight: 650; font-variant-numeric: tabular-nums; }
.difference .verdict { font-size: 16px; }
.difference .small { color: var(--muted); font-size: 12px; flex-basis: 100%; }
h2 { font-size: 15px; font-weight: 600; margin: 30px 0 8px; color: var(--text); }
.plots { display: grid; grid-template-columns: repeat(3, 1fr); gap: 14px; }
.plot { background: var(--panel); border: 1px solid var(--line); border-radius: 12px; padding: 8px 8px 4px; }
.plot svg { width: 100%; height: auto; display: block; }
.plot text { fill: var(--muted); font-size: 11px; font-family: inherit; }
.plot .axis { stroke: #4a4d55; stroke-width: 1; }
.plot .grid { stroke: #2e3137; stroke-width: 1; }
.plot .sample { fill: none; stroke: #8a877f; stroke-width: 1; stroke-opacity: 0.55; }
.plot .sample.model { stroke-dasharray: 2 3; }
.plot .sample:hover { stroke: #ddd; stroke-opacity: 1; stroke-width: 2; }
.plot .curve { fill: none; stroke-width: 2.4; }
.plot .curve.b { stroke-dasharray: 7 4; }
.legend { color: var(--muted); font-size: 12px; margin-top: 8px; }
.legend i { display: inline-block; width: 22px; height: 0; vertical-align: middle; margin: 0 5px 0 12px;
  border-top: 2.4px solid; }
.legend i.dash { border-top-style: dashed; }
.legend i.sample { border-top: 1px solid #8a877f; }
.about { color: var(--muted); font-size: 13px; max-width: 880px; }
.about p { margin: 6px 0; }
.about b { color: var(--text); font-weight: 600; }
@media (max-width: 1000px) { .metal { grid-template-columns: 1fr; } .plots { grid-template-columns: 1fr; } }
)CSS";

const char kExploreBody[] = R"HTML(<div class="wrap">
<header>
  <h1>alloycolor explorer · <span class="sys">@SYSTEM@</span></h1>
  <span class="model" id="model-line"></span>
</header>

<div class="toolbar">
  <div class="group"><span class="label">Light source</span>
    <span class="seg" id="ill-buttons" role="group" aria-label="illuminant"></span></div>
  <div class="group"><span class="label">Scene</span>
    <span class="seg" id="light-buttons" role="group" aria-label="lighting">
      <button type="button" data-light="studio" title="A product-shot light tent: key and fill softboxes, strip light, table">Studio</button>
      <button type="button" data-light="uniform" title="A uniform white surround: every pixel is the colour of the metal at its angle (as 'alloycolor render --light uniform')">Uniform</button>
    </span></div>
  <div class="group"><span class="label">Finish</span>
    <span class="seg" id="finish-buttons" role="group" aria-label="finish"></span></div>
  <div class="group"><span class="label">Angle</span>
    <input type="range" id="angle" min="0" max="90" step="any" value="0"
      title="Angle of incidence for the numbers below (0 = looking straight at the surface)">
    <input type="number" id="angle-value" min="0" max="90" step="1" value="0">°</div>
</div>

<section class="metal" id="metal-a">
  <div class="slider">
    <span class="tag">A</span>
    <div class="track"><input type="range" id="x-a" step="any" aria-label="composition A">
      <div class="ticks" id="ticks-a"></div></div>
    <input type="text" id="x-a-text" spellcheck="false"
      title="A composition: 0.75 (atomic fraction), 75at%, 75wt%, or a karat for gold (18k)">
    <div class="readout" id="a-readout"></div>
  </div>
  <div class="stage" id="stage-a"><canvas id="sphere-a"></canvas><canvas id="ring-a"></canvas></div>
  <div class="card" id="card-a"></div>
</section>

<div class="difference" id="difference">
  <div class="pair"><span id="pair-a"></span><span id="pair-b"></span></div>
  <div><div class="de">ΔE<sub>00</sub> <span id="de00"></span></div></div>
  <div class="verdict" id="verdict"></div>
  <div class="small" id="difference-note"></div>
</div>

<section class="metal" id="metal-b">
  <div class="slider">
    <span class="tag">B</span>
    <div class="track"><input type="range" id="x-b" step="any" aria-label="composition B">
      <div class="ticks" id="ticks-b"></div></div>
    <input type="text" id="x-b-text" spellcheck="false"
      title="A composition: 0.75 (atomic fraction), 75at%, 75wt%, or a karat for gold (18k)">
    <div class="readout" id="b-readout"></div>
  </div>
  <div class="stage" id="stage-b"><canvas id="sphere-b"></canvas><canvas id="ring-b"></canvas></div>
  <div class="card" id="card-b"></div>
</section>

<h2>Optical constants and reflectance</h2>
<div class="plots">
  <div class="plot"><svg id="plot-n" viewBox="0 0 340 230"></svg></div>
  <div class="plot"><svg id="plot-k" viewBox="0 0 340 230"></svg></div>
  <div class="plot"><svg id="plot-r" viewBox="0 0 340 230"></svg></div>
</div>
<div class="legend" id="legend"></div>

<h2>How this page computes</h2>
<div class="about" id="about"></div>
</div>
)HTML";

const char kExploreColourJs[] = R"JS(
"use strict";
// The colour formulas of colorimetry.h (CIE 15:2004 CIELAB, IEC 61966-2-1 sRGB, CIEDE2000
// after Sharma, Wu & Dalal 2005), the composition conversion of composition.h and the
// table interpolation of composition_table.h, in JavaScript. Pure functions, no page state.
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
  return { labFromXYZ, linearSRGBFromXYZ, srgbEncode, srgb8, hex, deltaE00, weightFromAtomic,
           atomicFromWeight, segmentWeights, findSegment };
})();
)JS";

}  // namespace alloycolor::app
