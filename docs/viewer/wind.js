// banyan's wind in three.js: the reference implementation of the model in
// docs/game-engines.md, the same one as the add-on's "Banyan Wind"
// Geometry Nodes modifier, so a plant sways alike in both.
//
// Every vertex of a plant carries the point it sways about (glTF
// _WIND_PIVOT_X/_Y/_Z, the node's frame) and _WIND_LEVEL, _WIND_STIFFNESS
// (s), _WIND_PHASE, _WIND_FLUTTER, all float scalars (docs/gltf.md,
// "Wind"); GLTFLoader keeps them as the geometry attributes `_wind_pivot_x`,
// ... (it lower-cases names it does not know). The vertex shader, with d
// the wind's horizontal direction:
//  1. main bend, along d by
//       strength * (1 - s)^2 * h * (1 + gust * sin(2 pi (f t + phi_plant)))
//     h the height above the plant's lowest point (the bounding box of the
//     meshes of one glTF node), phi_plant one phase per instance;
//  2. secondary sway, a turn about the vertex's own pivot, about up x d, by
//       0.25 * strength * (1 - s) * sin(2 pi (2.3 f t + phase));
//  3. leaf flutter along the rest normal by
//       flutter * flutter_weight * sin(2 pi (3.7 f t + phase)).
// The normal turns with 2 (and leans with the shear of 1). Defaults and
// rates are the add-on's (blender_addon/banyan/wind.py).
import * as THREE from 'three';

// The geometry attributes the shader reads (wind_level is not needed).
export const WIND_ATTRIBUTES = ['_wind_pivot_x', '_wind_pivot_y', '_wind_pivot_z', '_wind_stiffness', '_wind_phase',
  '_wind_flutter'];

// The defaults, in the add-on's units: strength in radians (the steady
// lean of a vertex of stiffness 0), gust the swing relative to that lean,
// frequency in Hz, direction in degrees counter-clockwise from banyan's +x
// seen from above (z up), flutter in metres.
export const WIND_DEFAULTS = Object.freeze({
  strength: 0.06, gust: 0.6, frequency: 0.35, direction: 0, flutter: 0.01,
});
const FLUTTER_RATE = 3.7;   // leaves flutter this many times faster than the gusts (the add-on's FLUTTER_RATIO)
const SWAY_RATE = 2.3;      // the secondary sway's rate (the add-on's SWAY_RATIO; its share SWAY 0.25 is in the shader)

export function hasWind(geometry) {
  const a = geometry.attributes;
  return WIND_ATTRIBUTES.every((k) => a[k] && a[k].itemSize === 1);
}

const DECLARATIONS = /* glsl */`
attribute float _wind_pivot_x, _wind_pivot_y, _wind_pivot_z;
attribute float _wind_stiffness, _wind_phase, _wind_flutter;
uniform vec3 banyanWindAxis;   // world axis the wind turns things about (unit, horizontal)
uniform float banyanWindStrength, banyanWindGust, banyanWindCycle, banyanWindFlutter, banyanWindFlutterCycle;
uniform float banyanWindSwayCycle;
uniform float banyanWindBase;   // the plant's lowest y (its own frame)
uniform float banyanWindUnit;   // metres per unit of that frame (a compact file's node scale; else 1)

// Rotation by angle a (radians) about the unit axis k (Rodrigues).
mat3 banyanWindRotation(vec3 k, float a) {
  float c = cos(a), s = sin(a), t = 1.0 - c;
  return mat3(t * k.x * k.x + c,       t * k.x * k.y + s * k.z, t * k.x * k.z - s * k.y,
              t * k.x * k.y - s * k.z, t * k.y * k.y + c,       t * k.y * k.z + s * k.x,
              t * k.x * k.z + s * k.y, t * k.y * k.z - s * k.x, t * k.z * k.z + c);
}
`;

// After beginnormal_vertex (objectNormal exists, positions not yet), in
// the mesh's own frame (y up, glTF). The world wind goes into that frame
// through the model (and instance) matrix, so turned or instanced trees
// all lean downwind. Instances differ in phi_plant by where they stand,
// so copies of one variant do not sway in step.
const ANGLE = /* glsl */`
mat3 banyanToWorld = mat3(modelMatrix);
float banyanPlant = 0.0;
#ifdef USE_INSTANCING
  banyanToWorld = banyanToWorld * mat3(instanceMatrix);
  banyanPlant = fract(dot(instanceMatrix[3].xyz, vec3(0.0713, 0.0, 0.1371)));
#endif
mat3 banyanToLocal = transpose(banyanToWorld);
vec3 banyanAxis = normalize(banyanToLocal * banyanWindAxis);
// d = axis x up in the mesh frame: the wind's horizontal direction.
vec3 banyanDir = normalize(cross(banyanAxis, vec3(0.0, 1.0, 0.0)));
float banyanFree = 1.0 - _wind_stiffness;
float banyanBend = banyanWindStrength * banyanFree * banyanFree *
                   (sin(6.28318531 * fract(banyanWindCycle + banyanPlant)) * banyanWindGust + 1.0);
float banyanAngle = 0.25 * banyanWindStrength * banyanFree *
                    sin(6.28318531 * (banyanWindSwayCycle + _wind_phase));
mat3 banyanTurn = banyanWindRotation(banyanAxis, banyanAngle);
vec3 banyanRestNormal = objectNormal;
// The bend is the shear x += bend h d: normals by its inverse transpose.
objectNormal = banyanTurn * (objectNormal - banyanBend * dot(objectNormal, banyanDir) * vec3(0.0, 1.0, 0.0));
#ifdef USE_TANGENT
  objectTangent = banyanTurn * objectTangent;
#endif
`;

// After begin_vertex: turn about the pivot, bend, flutter. R d - d rather
// than pivot + R d: with the wind off every term is exactly 0, and the
// file's positions come through bit for bit.
const MOVE = /* glsl */`
vec3 banyanArm = transformed - vec3(_wind_pivot_x, _wind_pivot_y, _wind_pivot_z);
float banyanH = transformed.y - banyanWindBase;
transformed += banyanTurn * banyanArm - banyanArm;
transformed += banyanDir * (banyanBend * banyanH);
transformed += banyanRestNormal * (banyanWindFlutter * _wind_flutter *
               sin(6.28318531 * (banyanWindFlutterCycle + _wind_phase))) / banyanWindUnit;
`;

export class Wind {
  constructor({ enabled = true } = {}) {
    // time: null follows the clock; a number (seconds) freezes it there.
    this.settings = { enabled, ...WIND_DEFAULTS, time: null };
    this.clock0 = performance.now();
    this.uniforms = {
      banyanWindAxis: { value: new THREE.Vector3(0, 0, -1) },
      banyanWindStrength: { value: 0 },
      banyanWindGust: { value: 0 },
      banyanWindCycle: { value: 0 },
      banyanWindFlutter: { value: 0 },
      banyanWindFlutterCycle: { value: 0 },
      banyanWindSwayCycle: { value: 0 },
    };
    this.patched = new Map();
    this.bases = new WeakMap();   // mesh: its plant's lowest y (attach)
  }

  // True while the picture changes by itself.
  running() {
    return this.settings.enabled && this.settings.time === null && this.settings.strength + this.settings.flutter > 0;
  }

  now() {
    return this.settings.time ?? (performance.now() - this.clock0) / 1000;
  }

  // Sets the shared uniforms for this frame. Off: every amplitude 0, which
  // leaves positions and normals exactly as in the file.
  update() {
    const s = this.settings, u = this.uniforms, on = s.enabled;
    const d = THREE.MathUtils.degToRad(s.direction);
    // banyan's wind (cos d, sin d, 0), z up; the axis up x wind is
    // (-sin d, cos d, 0), which in glTF's y-up frame (x, z, -y) is
    // (-sin d, 0, -cos d). Turning about it tips +up toward the wind.
    u.banyanWindAxis.value.set(-Math.sin(d), 0, -Math.cos(d));
    u.banyanWindStrength.value = on ? s.strength : 0;
    u.banyanWindGust.value = s.gust;
    u.banyanWindFlutter.value = on ? s.flutter : 0;
    // Cycles rather than raw time keep float32 precise after hours.
    const t = this.now();
    u.banyanWindCycle.value = (s.frequency * t) % 1;
    u.banyanWindFlutterCycle.value = (FLUTTER_RATE * s.frequency * t) % 1;
    u.banyanWindSwayCycle.value = (SWAY_RATE * s.frequency * t) % 1;
  }

  // Makes material sway (it must be used only on geometry with the wind
  // attributes); base: the plant's lowest y in the geometry's frame.
  // Returns it.
  patch(material, base = 0, unit = 1) {
    const uniforms = { ...this.uniforms, banyanWindBase: { value: base }, banyanWindUnit: { value: unit } };
    material.onBeforeCompile = (shader) => {
      if (!shader.vertexShader.includes('#include <beginnormal_vertex>') ||
          !shader.vertexShader.includes('#include <begin_vertex>')) return;
      Object.assign(shader.uniforms, uniforms);
      shader.vertexShader = shader.vertexShader
        .replace('#include <common>', `#include <common>\n${DECLARATIONS}`)
        .replace('#include <beginnormal_vertex>', `#include <beginnormal_vertex>\n${ANGLE}`)
        .replace('#include <begin_vertex>', `#include <begin_vertex>\n${MOVE}`);
    };
    material.customProgramCacheKey = () => 'banyan-wind-2';
    material.needsUpdate = true;
    return material;
  }

  // The plant base attach() found for mesh (0 when it did not see it).
  baseOf(mesh) {
    return this.bases.get(mesh) ?? 0;
  }

  // Gives every mesh under root that has the attributes a swaying copy of
  // its material (one copy per material and plant base); returns how many
  // meshes sway. A plant's base is the lowest y of its meshes: the
  // primitives of one glTF mesh (GLTFLoader's children of one node, at
  // the node's own frame) share it, so wood and leaves bend alike.
  attach(root) {
    let n = 0;
    const copies = new Map();
    const bases = new Map();
    const plant = (o) => (o.parent && o.position.lengthSq() === 0 && o.quaternion.w === 1 &&
                          o.scale.x === 1 && o.scale.y === 1 && o.scale.z === 1) ? o.parent : o;
    root.traverse((o) => {
      if (!o.isMesh || !hasWind(o.geometry)) return;
      if (!o.geometry.boundingBox) o.geometry.computeBoundingBox();
      const k = plant(o), y = o.geometry.boundingBox.min.y;
      bases.set(k, Math.min(bases.get(k) ?? Infinity, y));
    });
    root.traverse((o) => {
      if (!o.isMesh || !hasWind(o.geometry)) return;
      const base = bases.get(plant(o));
      // A compact file's positions and pivots are in steps of its node's
      // (uniform) scale: the turn and the bend do not depend on the unit,
      // the flutter (metres along the normal) does.
      const unit = plant(o).scale.x;
      this.bases.set(o, base);
      const one = (m) => {
        const key = `${m.uuid}:${base}:${unit}`;
        if (!copies.has(key)) copies.set(key, this.patch(m.clone(), base, unit));
        return copies.get(key);
      };
      o.material = Array.isArray(o.material) ? o.material.map(one) : one(o.material);
      // The swaying mesh leaves its rest bounds a little; never cull it.
      o.frustumCulled = false;
      n++;
    });
    return n;
  }
}
