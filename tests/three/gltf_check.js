// For each glTF file named in ?files=, loads it with GLTFLoader, renders a sphere with its
// first material (metallic-roughness PBR) under a uniform white environment of radiance 1
// (no tone mapping, sRGB output, orthographic camera looking down the sphere's axis) and
// reads the 8-bit sRGB centre pixel, where the view is normal to the surface: three.js's
// image-based specular is F0 * A + F90 * B there (its DFG table at mu = 1), about F0.
// The result is JSON text in #result: {three, files: [{file, centre (8-bit sRGB),
// centre_linear, baseColorFactor, material, extensions}], warnings: [...]}; any console
// warning or error and any loader error is listed in warnings. (GLTFLoader warns of an
// unknown extension only when it is required; extensions lists extensionsUsed.)
import * as THREE from 'three';
import {GLTFLoader} from 'three/addons/loaders/GLTFLoader.js';

const warnings = [];
for (const level of ['warn', 'error']) {
  const original = console[level].bind(console);
  console[level] = (...args) => {
    warnings.push(level + ': ' + args.map(String).join(' '));
    original(...args);
  };
}
window.addEventListener('error', (e) => warnings.push('page error: ' + e.message));
window.addEventListener('unhandledrejection', (e) => warnings.push('rejection: ' + e.reason));

const kSize = 65;  // odd: one pixel sits on the centre of the sphere

function WhiteEnvironment(renderer) {
  const data = new Float32Array(16 * 8 * 4).fill(1);
  const equirect = new THREE.DataTexture(data, 16, 8, THREE.RGBAFormat, THREE.FloatType);
  equirect.mapping = THREE.EquirectangularReflectionMapping;
  equirect.colorSpace = THREE.LinearSRGBColorSpace;
  equirect.needsUpdate = true;
  const pmrem = new THREE.PMREMGenerator(renderer);
  const target = pmrem.fromEquirectangular(equirect);
  pmrem.dispose();
  return target.texture;
}

function Load(loader, file) {
  return new Promise((resolve, reject) => loader.load(file, resolve, undefined, reject));
}

async function Check(renderer, environment, loader, file) {
  const gltf = await Load(loader, file);
  const material = await gltf.parser.getDependency('material', 0);
  const scene = new THREE.Scene();
  scene.environment = environment;
  scene.background = new THREE.Color(0, 0, 0);
  scene.add(new THREE.Mesh(new THREE.SphereGeometry(1, 256, 128), material));
  const camera = new THREE.OrthographicCamera(-1.1, 1.1, 1.1, -1.1, 0.1, 10);
  camera.position.set(0, 0, 5);
  camera.lookAt(0, 0, 0);
  renderer.render(scene, camera);
  const gl = renderer.getContext();
  const pixel = new Uint8Array(4);
  const c = (kSize - 1) / 2;
  gl.readPixels(c, c, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
  // The same picture in linear floats (a render target gets no output encoding): the
  // reflectance three.js computes at the centre, before 8-bit rounding.
  const target = new THREE.WebGLRenderTarget(kSize, kSize, {type: THREE.FloatType});
  renderer.setRenderTarget(target);
  renderer.render(scene, camera);
  const linear = new Float32Array(4);
  renderer.readRenderTargetPixels(target, c, c, 1, 1, linear);
  renderer.setRenderTarget(null);
  target.dispose();
  return {
    file,
    centre: Array.from(pixel.slice(0, 3)),
    centre_linear: Array.from(linear.slice(0, 3)),
    baseColorFactor: material.color.toArray(),
    material: {
      type: material.type,
      metalness: material.metalness,
      roughness: material.roughness,
      name: material.name,
    },
    extensions: gltf.parser.json.extensionsUsed || [],
  };
}

async function Main() {
  const files = (new URLSearchParams(location.search).get('files') || '').split(',');
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = kSize;
  document.body.appendChild(canvas);
  const renderer = new THREE.WebGLRenderer({canvas, antialias: false, preserveDrawingBuffer: true});
  renderer.setPixelRatio(1);
  renderer.setSize(kSize, kSize, false);
  renderer.toneMapping = THREE.NoToneMapping;
  renderer.outputColorSpace = THREE.SRGBColorSpace;
  const environment = WhiteEnvironment(renderer);
  const loader = new GLTFLoader();
  const results = [];
  for (const file of files) {
    try {
      results.push(await Check(renderer, environment, loader, file));
    } catch (e) {
      warnings.push('loader error (' + file + '): ' + (e && e.message ? e.message : e));
    }
  }
  return results;
}

const out = document.getElementById('result');
Main()
    .then((files) => {
      out.textContent = JSON.stringify({three: THREE.REVISION, files, warnings});
    })
    .catch((e) => {
      warnings.push('failed: ' + (e && e.stack ? e.stack : e));
      out.textContent = JSON.stringify({three: THREE.REVISION, files: [], warnings});
    })
    .finally(() => out.setAttribute('data-done', 'true'));
