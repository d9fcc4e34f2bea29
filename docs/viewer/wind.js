// banyan's wind in three.js: the reference implementation of the model in
// docs/game-engines.md, the same one as the add-on's "Banyan Wind"
// Geometry Nodes modifier, so a plant sways alike in both.
//
// Every vertex of a plant carries the point it sways about (glTF
// _WIND_PIVOT, VEC3, the node's frame) and _WIND_PARAMS (VEC4: level,
// stiffness, phase, flutter); GLTFLoader keeps them as the geometry
// attributes `_wind_pivot` and `_wind_params` (it lower-cases names it does
// not know). The vertex shader turns the vertex about its pivot by
//
//   angle = strength * (1 - stiffness) * (sin(2 pi (f t + phase)) * gust + 1)
//
// about the horizontal axis perpendicular to the wind (so a tip leans
// downwind and swings about that lean), then moves it along its normal by
//   flutter * flutter_weight * sin(2 pi (3.7 f t + phase))
// along its rest normal (leaves only: wood has flutter weight 0). The
// normal turns with the vertex. Defaults and the flutter rate are the
// add-on's (blender_addon/banyan/wind.py). One pivot per vertex: a branch sways about its own base but does
// not carry its children with it (Pivot Painter 2 chains up to four
// levels), which is why the angles stay small.
import * as THREE from 'three';

export const WIND_PARAMS = ['wind_level', 'wind_stiffness', 'wind_phase', 'wind_flutter'];

// The defaults, in the add-on's units: strength in radians (the steady
// lean of a vertex of stiffness 0), gust the swing relative to that lean,
// frequency in Hz, direction in degrees counter-clockwise from banyan's +x
// seen from above (z up), flutter in metres.
export const WIND_DEFAULTS = Object.freeze({
  strength: 0.06, gust: 0.6, frequency: 0.35, direction: 0, flutter: 0.01,
});
const FLUTTER_RATE = 3.7;   // leaves flutter this many times faster than the gusts (the add-on's FLUTTER_RATIO)

export function hasWind(geometry) {
  const a = geometry.attributes;
  return !!(a._wind_pivot && a._wind_params && a._wind_pivot.itemSize === 3 && a._wind_params.itemSize === 4);
}

const DECLARATIONS = /* glsl */`
attribute vec3 _wind_pivot;
attribute vec4 _wind_params;   // level, stiffness, phase, flutter
uniform vec3 banyanWindAxis;   // world axis the wind turns things about (unit, horizontal)
uniform float banyanWindStrength, banyanWindGust, banyanWindCycle, banyanWindFlutter, banyanWindFlutterCycle;

// Rotation by angle a (radians) about the unit axis k (Rodrigues).
mat3 banyanWindRotation(vec3 k, float a) {
  float c = cos(a), s = sin(a), t = 1.0 - c;
  return mat3(t * k.x * k.x + c,       t * k.x * k.y + s * k.z, t * k.x * k.z - s * k.y,
              t * k.x * k.y - s * k.z, t * k.y * k.y + c,       t * k.y * k.z + s * k.x,
              t * k.x * k.z + s * k.y, t * k.y * k.z - s * k.x, t * k.z * k.z + c);
}
`;

// After beginnormal_vertex (objectNormal exists, positions not yet):
// the angle, in the mesh's own frame. The world wind axis goes into that
// frame through the model (and instance) matrix, so turned or instanced
// trees all lean downwind. Instances differ in phase by where they stand,
// so copies of one variant do not sway in step.
const ANGLE = /* glsl */`
mat3 banyanToWorld = mat3(modelMatrix);
float banyanPhase = _wind_params.z;
#ifdef USE_INSTANCING
  banyanToWorld = banyanToWorld * mat3(instanceMatrix);
  banyanPhase += fract(dot(instanceMatrix[3].xyz, vec3(0.0713, 0.0, 0.1371)));
#endif
vec3 banyanAxis = normalize(transpose(banyanToWorld) * banyanWindAxis);
float banyanAngle = banyanWindStrength * (1.0 - _wind_params.y) *
                    (sin(6.28318531 * (banyanWindCycle + banyanPhase)) * banyanWindGust + 1.0);
mat3 banyanTurn = banyanWindRotation(banyanAxis, banyanAngle);
vec3 banyanRestNormal = objectNormal;
objectNormal = banyanTurn * objectNormal;
#ifdef USE_TANGENT
  objectTangent = banyanTurn * objectTangent;
#endif
`;

// After begin_vertex: turn the position about the pivot, then flutter.
const MOVE = /* glsl */`
// R d - d rather than pivot + R d: with the wind off R is exactly the
// identity, and the file's positions come through bit for bit.
vec3 banyanArm = transformed - _wind_pivot;
transformed += banyanTurn * banyanArm - banyanArm;
transformed += banyanRestNormal * (banyanWindFlutter * _wind_params.w *
               sin(6.28318531 * (banyanWindFlutterCycle + banyanPhase)));
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
    };
    this.patched = new Map();
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
  }

  // Makes material sway (it must be used only on geometry with the wind
  // attributes). Returns it.
  patch(material) {
    const uniforms = this.uniforms;
    material.onBeforeCompile = (shader) => {
      if (!shader.vertexShader.includes('#include <beginnormal_vertex>') ||
          !shader.vertexShader.includes('#include <begin_vertex>')) return;
      Object.assign(shader.uniforms, uniforms);
      shader.vertexShader = shader.vertexShader
        .replace('#include <common>', `#include <common>\n${DECLARATIONS}`)
        .replace('#include <beginnormal_vertex>', `#include <beginnormal_vertex>\n${ANGLE}`)
        .replace('#include <begin_vertex>', `#include <begin_vertex>\n${MOVE}`);
    };
    material.customProgramCacheKey = () => 'banyan-wind-1';
    material.needsUpdate = true;
    return material;
  }

  // Gives every mesh under root that has the attributes a swaying copy of
  // its material (one copy per material); returns how many meshes sway.
  attach(root) {
    let n = 0;
    const copies = new Map();
    root.traverse((o) => {
      if (!o.isMesh || !hasWind(o.geometry)) return;
      const one = (m) => {
        if (!copies.has(m)) copies.set(m, this.patch(m.clone()));
        return copies.get(m);
      };
      o.material = Array.isArray(o.material) ? o.material.map(one) : one(o.material);
      // The swaying mesh leaves its rest bounds a little; never cull it.
      o.frustumCulled = false;
      n++;
    });
    return n;
  }
}
