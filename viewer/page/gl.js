// The WebGL2 renderer: lit triangle meshes in one colour (the part, the cutter),
// the stock coloured by deviation in the shader (so a new colour range is only new
// uniforms), and line sets (the tool path, the origin axes, the measurement) with
// a motion range outside which their vertices are not drawn.

import { COLOURS } from './colour.js';

const SURFACE_VS = `#version 300 es
in vec3 aPos;
in vec3 aNormal;
in float aDev;
in float aState;
uniform mat4 uModel;
uniform mat4 uViewProj;
out vec3 vNormal;
out float vDev;
out float vState;
void main() {
  vNormal = mat3(uModel) * aNormal;
  vDev = aDev;
  vState = aState;
  gl_Position = uViewProj * uModel * vec4(aPos, 1.0);
}`;

const SURFACE_FS = `#version 300 es
precision highp float;
in vec3 vNormal;
in float vDev;
in float vState;
uniform int uByDeviation;
uniform vec3 uColour;
uniform vec3 uLight;
uniform vec3 uScale; // lo, hi, tol (mm)
uniform vec3 uRamp[9]; // neutral, excess pale, deep, beyond, gouge pale, deep, beyond, unmeasured, off the part
out vec4 colour;
vec3 deviation(float d) {
  if (vState > 1.5) return uRamp[8];
  if (vState > 0.5) return uRamp[7];
  if (abs(d) <= uScale.z) return uRamp[0];
  if (d > uScale.y) return uRamp[3];
  if (d < uScale.x) return uRamp[6];
  if (d > 0.0) return mix(uRamp[1], uRamp[2], (d - uScale.z) / max(uScale.y - uScale.z, 1e-12));
  return mix(uRamp[4], uRamp[5], (-d - uScale.z) / max(-uScale.x - uScale.z, 1e-12));
}
void main() {
  vec3 base = uByDeviation == 1 ? deviation(vDev) : uColour;
  vec3 n = normalize(vNormal);
  float lit = 0.62 + 0.38 * abs(dot(n, uLight));
  colour = vec4(base * lit, 1.0);
}`;

const LINE_VS = `#version 300 es
in vec3 aPos;
in float aMotion;
uniform mat4 uViewProj;
out float vMotion;
void main() {
  vMotion = aMotion;
  gl_Position = uViewProj * vec4(aPos, 1.0);
}`;

const LINE_FS = `#version 300 es
precision highp float;
in float vMotion;
uniform vec3 uColour;
uniform vec2 uRange;
out vec4 colour;
void main() {
  if (vMotion < uRange.x - 0.5 || vMotion > uRange.y + 0.5) discard;
  colour = vec4(uColour, 1.0);
}`;

const RAMP = ['neutral', 'excessPale', 'excessDeep', 'excessBeyond', 'gougePale', 'gougeDeep', 'gougeBeyond', 'unmeasured', 'offPart'];
const unit = (rgb) => rgb.map((c) => c / 255);

function compile(gl, vs, fs) {
  const program = gl.createProgram();
  for (const [type, text] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
    const s = gl.createShader(type);
    gl.shaderSource(s, text);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(`shader: ${gl.getShaderInfoLog(s)}`);
    gl.attachShader(program, s);
  }
  ['aPos', 'aNormal', 'aDev', 'aState'].forEach((name, k) => gl.bindAttribLocation(program, k, name));
  gl.bindAttribLocation(program, 1, 'aMotion');
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(`shader: ${gl.getProgramInfoLog(program)}`);
  const uniforms = {};
  const n = gl.getProgramParameter(program, gl.ACTIVE_UNIFORMS);
  for (let k = 0; k < n; k += 1) {
    const name = gl.getActiveUniform(program, k).name.replace(/\[0\]$/, '');
    uniforms[name] = gl.getUniformLocation(program, name);
  }
  return { program, uniforms };
}

export class Renderer {
  constructor(canvas) {
    const gl = canvas.getContext('webgl2', { antialias: true, preserveDrawingBuffer: true });
    if (!gl) throw new Error('this browser has no WebGL2');
    this.gl = gl;
    this.canvas = canvas;
    this.surface = compile(gl, SURFACE_VS, SURFACE_FS);
    this.line = compile(gl, LINE_VS, LINE_FS);
    gl.enable(gl.DEPTH_TEST);
    gl.clearColor(244 / 255, 245 / 255, 247 / 255, 1);
  }

  // A vertex array of `attributes` ([location, data, size]) and `indices`.
  vertexArray(attributes, indices) {
    const gl = this.gl;
    const vao = gl.createVertexArray();
    gl.bindVertexArray(vao);
    for (const [loc, data, size] of attributes) {
      if (!data) continue;
      const b = gl.createBuffer();
      gl.bindBuffer(gl.ARRAY_BUFFER, b);
      gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
      gl.enableVertexAttribArray(loc);
      gl.vertexAttribPointer(loc, size, gl.FLOAT, false, 0, 0);
    }
    if (indices) {
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, gl.createBuffer());
      gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, indices, gl.STATIC_DRAW);
    }
    gl.bindVertexArray(null);
    return vao;
  }

  // A triangle mesh: positions, normals, and for the stock deviations and states.
  // { kind: 'surface', count, indexed, byDeviation, colour, model }.
  surfaceItem({ pos, normal, dev, state, indices, colour }) {
    const vao = this.vertexArray([[0, pos, 3], [1, normal, 3], [2, dev, 1], [3, state, 1]], indices);
    return {
      kind: 'surface',
      vao,
      count: indices ? indices.length : pos.length / 3,
      indexed: Boolean(indices),
      byDeviation: Boolean(dev),
      hasNormal: Boolean(normal),
      colour: unit(colour ?? [255, 255, 255]),
      model: null,
      visible: true,
    };
  }

  // A set of line segments (pairs of points) with the motion index of each vertex.
  lineItem({ pos, motion, colour }) {
    const vao = this.vertexArray([[0, pos, 3], [1, motion, 1]], null);
    return { kind: 'line', vao, count: pos.length / 3, colour: unit(colour), hasMotion: Boolean(motion), range: [-Infinity, Infinity], visible: true };
  }

  // Draws `items` with the projection-view matrix `viewProj`, the deviation
  // `scale` and the light direction `light` (world frame).
  draw(items, viewProj, scale, light) {
    const gl = this.gl;
    gl.viewport(0, 0, this.canvas.width, this.canvas.height);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    const s = this.surface;
    gl.useProgram(s.program);
    gl.uniformMatrix4fv(s.uniforms.uViewProj, false, viewProj);
    gl.uniform3fv(s.uniforms.uLight, light);
    gl.uniform3f(s.uniforms.uScale, scale.lo, scale.hi, scale.tol);
    gl.uniform3fv(s.uniforms.uRamp, RAMP.flatMap((k) => unit(COLOURS[k])));
    const ident = new Float32Array([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);
    gl.enable(gl.POLYGON_OFFSET_FILL);
    gl.polygonOffset(1, 1);
    for (const it of items) {
      if (it.kind !== 'surface' || !it.visible) continue;
      gl.uniformMatrix4fv(s.uniforms.uModel, false, it.model ?? ident);
      gl.uniform1i(s.uniforms.uByDeviation, it.byDeviation ? 1 : 0);
      gl.uniform3fv(s.uniforms.uColour, it.colour);
      gl.bindVertexArray(it.vao);
      if (!it.hasNormal) gl.vertexAttrib3f(1, 0, 0, 1);
      if (!it.byDeviation) {
        gl.vertexAttrib1f(2, 0);
        gl.vertexAttrib1f(3, 0);
      }
      if (it.indexed) gl.drawElements(gl.TRIANGLES, it.count, gl.UNSIGNED_INT, 0);
      else gl.drawArrays(gl.TRIANGLES, 0, it.count);
    }
    gl.disable(gl.POLYGON_OFFSET_FILL);
    const l = this.line;
    gl.useProgram(l.program);
    gl.uniformMatrix4fv(l.uniforms.uViewProj, false, viewProj);
    for (const it of items) {
      if (it.kind !== 'line' || !it.visible) continue;
      gl.uniform3fv(l.uniforms.uColour, it.colour);
      gl.uniform2f(l.uniforms.uRange, Math.max(it.range[0], -3e38), Math.min(it.range[1], 3e38));
      gl.bindVertexArray(it.vao);
      if (!it.hasMotion) gl.vertexAttrib1f(1, 0);
      gl.drawArrays(gl.LINES, 0, it.count);
    }
    gl.bindVertexArray(null);
  }
}
