// See three_render.html. Query: model (file name served under /model/), node (part of the mesh
// name, default "sphere"), width, height, distance (camera on +z, metres), fov (vertical, degrees),
// light (x,y,z towards the light), irradiance (the light's intensity: lux in three.js's
// physical units, i.e. irradiance on a surface facing it). Posts three.js's reading of the
// material and two pictures (RGBA floats, rows bottom-up): "shipped" and "spec" (below).
import * as THREE from 'three';
import {GLTFLoader} from 'three/addons/loaders/GLTFLoader.js';

async function post(path, text) {
  await fetch(path, {method: 'POST', body: text});
}

// three.js adds two terms to the glTF BRDF for punctual lights (docs/gltf.md): a multiple-
// scattering compensation of the specular lobe, 1 + f0 (1/E_ss − 1) from its DFG table, and a
// roughness increase by the screen-space change of the normal (geometric specular
// anti-aliasing). In the "spec" picture both are taken out of the shader, so it shows the
// specification's BRDF; a replacement that finds nothing is an error, never a silent no-op.
function specificationOnly(material) {
  const edits = [
    ['lights_fragment_begin', /material\.multiScatteringCompensation = [^;]*;/,
     'material.multiScatteringCompensation = vec3( 1.0 );'],
    ['lights_physical_fragment', /material\.roughness \+= geometryRoughness;/, ''],
  ];
  material.onBeforeCompile = (shader) => {
    for (const [chunk, pattern, replacement] of edits) {
      const text = THREE.ShaderChunk[chunk];
      if (!pattern.test(text)) throw new Error('three.js ' + chunk + ' no longer holds ' + pattern);
      shader.fragmentShader =
          shader.fragmentShader.replace('#include <' + chunk + '>', text.replace(pattern, replacement));
    }
  };
  material.needsUpdate = true;
}

function numbers(text) {
  return text.split(',').map(Number);
}

async function main() {
  const q = new URLSearchParams(location.search);
  const width = Number(q.get('width') ?? 128);
  const height = Number(q.get('height') ?? 128);
  const gltf = await new GLTFLoader().loadAsync('/model/' + q.get('model'));
  const wanted = q.get('node') ?? 'sphere';
  let found = null;
  gltf.scene.traverse((object) => {
    // GLTFLoader names a mesh after its node (spaces become underscores) or the node's child.
    const names = [object.name, object.parent?.name ?? ''];
    if (object.isMesh && found === null && names.some((name) => name.includes(wanted))) {
      found = object;
    }
  });
  if (found === null) throw new Error('no mesh named ' + wanted + ' in ' + q.get('model'));

  // The file's geometry and material on a scene of our own: the node's placement is the
  // file's business, the comparison needs the sphere at the origin, radius 1.
  const scene = new THREE.Scene();
  const sphere = new THREE.Mesh(found.geometry, found.material);
  found.geometry.computeBoundingSphere();
  sphere.scale.setScalar(1 / found.geometry.boundingSphere.radius);
  scene.add(sphere);
  const light = new THREE.DirectionalLight(0xffffff, Number(q.get('irradiance') ?? 1));
  light.position.set(...numbers(q.get('light') ?? '0,0,1'));
  scene.add(light);  // target defaults to the origin
  const camera = new THREE.PerspectiveCamera(Number(q.get('fov') ?? 1), width / height, 0.1, 100);
  camera.position.set(0, 0, Number(q.get('distance') ?? 10));
  camera.up.set(0, 1, 0);
  camera.lookAt(0, 0, 0);

  const renderer = new THREE.WebGLRenderer({antialias: false});
  renderer.toneMapping = THREE.NoToneMapping;
  renderer.setSize(width, height);
  const target = new THREE.WebGLRenderTarget(width, height, {type: THREE.FloatType});
  renderer.setRenderTarget(target);
  renderer.setClearColor(0x000000, 0);
  function draw(material) {
    sphere.material = material;
    renderer.render(scene, camera);
    const pixels = new Float32Array(width * height * 4);
    renderer.readRenderTargetPixels(target, 0, 0, width, height, pixels);
    return Array.from(pixels);
  }
  // Both pictures from one page load: three.js as shipped, and the specification's BRDF.
  const spec = found.material.clone();
  specificationOnly(spec);
  const images = {shipped: draw(found.material), spec: draw(spec)};

  const m = found.material;
  const material = {
    type: m.type,
    color: m.color.toArray(),
    metalness: m.metalness,
    roughness: m.roughness,
    ior: m.ior ?? null,
    specularIntensity: m.specularIntensity ?? null,
    specularColor: m.specularColor ? m.specularColor.toArray() : null,
  };
  await post('/result', JSON.stringify({
    three: THREE.REVISION,
    gl: renderer.getContext().getParameter(renderer.getContext().VERSION),
    width,
    height,
    rows: 'bottom-up',
    material,
    rgba: images,
  }));
}

main().catch((error) => post('/error', String(error && error.stack || error)));
