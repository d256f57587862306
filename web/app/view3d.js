// The debugger's 3D scene view (three.js): the scene's objects, lights and camera, and
// one pixel's ray tree from `rtk debug --json`, with orbit, zoom and pan. Every drawn
// object carries userData.rtk ('object', 'light', 'camera', 'ray', 'normal', 'marker')
// so the scene graph can be counted (web/test checks one object per primitive and one
// segment per ray).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { SVGRenderer } from 'three/addons/renderers/SVGRenderer.js';
import { Line2 } from 'three/addons/lines/Line2.js';
import { LineGeometry } from 'three/addons/lines/LineGeometry.js';
import { LineMaterial } from 'three/addons/lines/LineMaterial.js';

// Ray colours by kind; kinds this page does not know are drawn grey and dashed.
export const RAY_STYLE = {
  camera: { color: '#f5f5f5', label: 'camera ray (to the centre of projection)' },
  reflection: { color: '#4da3ff', label: 'reflection' },
  refraction: { color: '#3ddc84', label: 'refraction' },
  diffuse: { color: '#c8a2ff', label: 'diffuse bounce (Monte Carlo)' },
  glossy: { color: '#00d2d3', label: 'glossy reflection about a sampled half vector (Monte Carlo)' },
  shadow: { color: '#ffd84d', label: 'shadow ray, reaches the light' },
  'shadow-partial': { color: '#ff9f43', label: 'shadow ray through a transparent object' },
  'shadow-blocked': { color: '#ff4d4d', label: 'shadow ray, blocked (× at the blocker)' },
  normal: { color: '#e056fd', label: 'normal used at a hit' },
  other: { color: '#9aa0a6', label: 'other ray kinds', dashed: true },
};

const v3 = (a) => new THREE.Vector3(a[0], a[1], a[2]);
const toColor = (c) => new THREE.Color(Math.min(1, c[0]), Math.min(1, c[1]), Math.min(1, c[2]));

function webglAvailable() {
  try {
    const c = document.createElement('canvas');
    return !!(c.getContext('webgl2') || c.getContext('webgl'));
  } catch {
    return false;
  }
}

// Each ray of a debug document, depth first, with its parent's kind ('samples' at the top).
export function flattenRays(doc) {
  const out = [];
  const visit = (ray, level, sample) => {
    out.push({ ray, level, sample });
    for (const light of ray.lights) for (const s of light.shadow_rays) visit(s, level + 1, sample);
    for (const child of ray.children) visit(child, level + 1, sample);
  };
  doc.samples.forEach((ray, i) => visit(ray, 0, doc.sample ?? i));
  return out;
}

export function shadowStyle(ray) {
  if (!ray.hit) return 'shadow';
  return ray.color.every((c) => c === 0) ? 'shadow-blocked' : 'shadow-partial';
}

export class SceneView {
  constructor(container) {
    this.container = container;
    this.webgl = webglAvailable();
    this.renderer = this.webgl ? new THREE.WebGLRenderer({ antialias: true }) : new SVGRenderer();
    if (this.webgl) this.renderer.setPixelRatio(window.devicePixelRatio);
    this.renderer.setClearColor?.(0x14171c);
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0x14171c);
    this.camera = new THREE.PerspectiveCamera(45, 1, 0.01, 1000);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.enableDamping = false;
    this.controls.screenSpacePanning = true;
    this.controls.addEventListener('change', () => this.draw());
    this.scene.add(new THREE.AmbientLight(0xffffff, 1.2));
    const sun = new THREE.DirectionalLight(0xffffff, 1.6);
    sun.position.set(3, 5, 4);
    this.scene.add(sun);
    this.objects = new THREE.Group();
    this.rays = new THREE.Group();
    this.scene.add(this.objects, this.rays);
    new ResizeObserver(() => this.resize()).observe(container);
  }

  resize() {
    const w = this.container.clientWidth, h = this.container.clientHeight;
    if (!w || !h) return;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.rays.traverse((o) => o.material?.resolution?.set(w, h));
    this.draw();
  }

  draw() { this.renderer.render(this.scene, this.camera); }

  clear(group) {
    for (const child of [...group.children]) {
      group.remove(child);
      child.traverse((o) => { o.geometry?.dispose(); o.material?.dispose?.(); });
    }
  }

  // view: rtk_scene_json's document with positions and triangles (Rtk.sceneView).
  setScene(view) {
    this.clear(this.objects);
    this.clear(this.rays);
    this.treeBox = null;
    this.view = view;
    const box = new THREE.Box3();
    for (const o of view.objects) {
      const color = o.diffuse.some((c) => c > 0) ? toColor(o.diffuse) : o.emissive.some((c) => c > 0) ? toColor(o.emissive) : new THREE.Color(0.55, 0.55, 0.6);
      const clear = o.transmittance.some((c) => c > 0);
      const material = new THREE.MeshLambertMaterial({ color, transparent: clear, opacity: clear ? 0.35 : 1, side: THREE.DoubleSide, depthWrite: !clear });
      let mesh;
      if (o.kind === 'mesh') {
        const g = new THREE.BufferGeometry();
        const idx = view.triangles.subarray(o.first_triangle * 3, (o.first_triangle + o.triangle_count) * 3);
        g.setAttribute('position', new THREE.BufferAttribute(view.positions, 3));
        g.setIndex(new THREE.BufferAttribute(Uint32Array.from(idx), 1));
        g.computeVertexNormals();
        mesh = new THREE.Mesh(g, material);
      } else {
        // The format's unit shapes: a sphere of radius 0.5, a cylinder of radius 0.5 on y in [-0.5, 0.5].
        const g = o.kind === 'sphere' ? new THREE.SphereGeometry(0.5, 32, 16) : new THREE.CylinderGeometry(0.5, 0.5, 1, 32);
        mesh = new THREE.Mesh(g, material);
        const m = o.to_world;
        mesh.matrixAutoUpdate = false;
        mesh.matrix.set(m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8], m[9], m[10], m[11], 0, 0, 0, 1);
      }
      mesh.userData = { rtk: 'object', index: o.index, node: o.node, kind: o.kind };
      mesh.name = o.node;
      this.objects.add(mesh);
      mesh.updateMatrixWorld(true);
      box.expandByObject(mesh);
    }
    const c = view.camera;
    box.expandByPoint(v3(c.eye));
    this.center = box.getCenter(new THREE.Vector3());
    this.radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 1e-3);
    this.addLights(view.lights);
    this.addCamera(c);
    this.camera.near = this.radius / 1000;
    this.camera.far = this.radius * 100;
    this.resetView();
  }

  // Looks at the pixel's ray tree when there is one (else the whole scene) from beside
  // the render camera, so both the tree and where it started are in view.
  resetView() {
    const tree = this.treeBox && !this.treeBox.isEmpty() ? this.treeBox : null;
    const center = tree ? tree.getCenter(new THREE.Vector3()) : this.center;
    const radius = tree ? Math.max(tree.getSize(new THREE.Vector3()).length() / 2, this.radius * 0.2) : this.radius;
    const out = v3(this.view.camera.eye).sub(center);
    if (out.lengthSq() === 0) out.set(0, 0, 1);
    out.normalize().multiplyScalar(radius * 2.4).applyAxisAngle(new THREE.Vector3(0, 1, 0), 0.6);
    out.y += radius * 0.5;
    this.camera.position.copy(center).add(out);
    this.controls.target.copy(center);
    this.camera.updateProjectionMatrix();
    this.controls.update();
    this.draw();
  }

  addLights(lights) {
    const r = this.radius;
    for (const l of lights) {
      const color = toColor(l.color.map((x) => Math.max(x, 0.35)));
      let obj;
      if (l.kind === 'directional') {
        const dir = v3(l.direction).normalize();
        obj = new THREE.ArrowHelper(dir.clone().negate(), this.center.clone().add(dir.clone().multiplyScalar(r * 1.2)), r * 0.4, 0xffd84d, r * 0.1, r * 0.05);
      } else if (l.kind === 'area') {
        const g = new THREE.BufferGeometry().setFromPoints([v3(l.corner), v3(l.corner).add(v3(l.edge_u)), v3(l.corner).add(v3(l.edge_u)).add(v3(l.edge_v)), v3(l.corner).add(v3(l.edge_v))]);
        g.setIndex([0, 1, 2, 0, 2, 3]);
        obj = new THREE.Mesh(g, new THREE.MeshBasicMaterial({ color: 0xfff3b0, side: THREE.DoubleSide }));
      } else {
        obj = new THREE.Mesh(new THREE.SphereGeometry(r * 0.03, 16, 8), new THREE.MeshBasicMaterial({ color: 0xffd84d }));
        obj.position.copy(v3(l.position));
      }
      obj.userData = { rtk: 'light', index: l.index, kind: l.kind, color };
      this.objects.add(obj);
    }
  }

  addCamera(c) {
    const eye = v3(c.eye), f = v3(c.forward), rt = v3(c.right), up = v3(c.up);
    const s = this.radius * 0.15, th = c.tan_half_fov, ta = th * c.aspect;
    const corner = (a, b) => eye.clone().add(f.clone().multiplyScalar(s)).add(rt.clone().multiplyScalar(a * ta * s)).add(up.clone().multiplyScalar(b * th * s));
    const k = [corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1)];
    const pts = [];
    for (let i = 0; i < 4; i++) pts.push(eye, k[i], k[i], k[(i + 1) % 4]);
    const frustum = new THREE.LineSegments(new THREE.BufferGeometry().setFromPoints(pts), new THREE.LineBasicMaterial({ color: 0x8ab4f8 }));
    frustum.userData = { rtk: 'camera' };
    this.objects.add(frustum);
  }

  // The end of a ray that hit nothing: on the light's square it ends on, towards its
  // light, or out of the scene.
  missEnd(ray) {
    if (ray.light_hit) return v3(ray.light_hit.point);
    const o = v3(ray.origin), d = v3(ray.direction).normalize();
    const light = ray.kind === 'shadow' ? this.view.lights[ray.light] : null;
    const len = light && light.kind !== 'directional' ? v3(light.position).distanceTo(o) : this.radius * 1.5;
    return o.add(d.multiplyScalar(len));
  }

  // A segment a few pixels wide (three's fat lines) under WebGL; a plain line otherwise.
  segment(start, end, color, dashed) {
    if (this.webgl) {
      const g = new LineGeometry().setPositions([start.x, start.y, start.z, end.x, end.y, end.z]);
      const m = new LineMaterial({ color, linewidth: 2.5, dashed: !!dashed, dashSize: this.radius * 0.03, gapSize: this.radius * 0.02, transparent: true });
      m.resolution.set(this.container.clientWidth || 800, this.container.clientHeight || 600);
      const line = new Line2(g, m);
      if (dashed) line.computeLineDistances();
      return line;
    }
    const g = new THREE.BufferGeometry().setFromPoints([start, end]);
    const line = new THREE.Line(g, dashed ? new THREE.LineDashedMaterial({ color, dashSize: this.radius * 0.03, gapSize: this.radius * 0.02 }) : new THREE.LineBasicMaterial({ color }));
    if (dashed) line.computeLineDistances();
    return line;
  }

  // Draws a debug document's rays and frames them.
  setTree(doc) {
    this.clear(this.rays);
    this.rayLines = [];
    if (!doc) return this.draw();
    const box = new THREE.Box3();
    for (const { ray } of flattenRays(doc)) {
      const style = ray.kind === 'shadow' ? shadowStyle(ray) : RAY_STYLE[ray.kind] ? ray.kind : 'other';
      const { color, dashed } = RAY_STYLE[style];
      const start = v3(ray.origin), end = ray.hit ? v3(ray.hit.point) : this.missEnd(ray);
      const line = this.segment(start, end, color, dashed);
      box.expandByPoint(start);
      if (ray.hit) box.expandByPoint(end); // misses run out of the scene: frame what was hit
      line.userData = { rtk: 'ray', kind: ray.kind, style, ray };
      this.rays.add(line);
      this.rayLines.push(line);
      if (ray.hit && ray.kind !== 'shadow' && ray.hit.normal_used) {
        const n = v3(ray.hit.normal_used).normalize().multiplyScalar(this.radius * 0.08);
        const normal = this.segment(end, end.clone().add(n), RAY_STYLE.normal.color);
        normal.userData = { rtk: 'normal' };
        this.rays.add(normal);
      }
      if (ray.hit) {
        const dot = new THREE.Mesh(new THREE.SphereGeometry(this.radius * (style === 'shadow-blocked' ? 0.012 : 0.008), 8, 6), new THREE.MeshBasicMaterial({ color }));
        dot.position.copy(end);
        dot.userData = { rtk: 'marker' };
        this.rays.add(dot);
        if (style === 'shadow-blocked') this.rays.add(this.cross(end, color));
      }
    }
    this.treeBox = box;
    this.resetView();
  }

  cross(at, color) {
    const s = this.radius * 0.03;
    const pts = [[-s, -s, 0], [s, s, 0], [-s, s, 0], [s, -s, 0], [0, -s, -s], [0, s, s], [0, -s, s], [0, s, -s]].map((p) => at.clone().add(new THREE.Vector3(...p)));
    const x = new THREE.LineSegments(new THREE.BufferGeometry().setFromPoints(pts), new THREE.LineBasicMaterial({ color }));
    x.userData = { rtk: 'marker' };
    return x;
  }

  // Emphasises one ray (index into flattenRays order) or none (-1).
  highlight(i) {
    (this.rayLines || []).forEach((line, j) => {
      line.material.opacity = i < 0 || i === j ? 1 : 0.25;
      line.material.transparent = !(i < 0 || i === j);
    });
    this.draw();
  }

  // What the scene graph holds, by userData.rtk kind.
  counts() {
    const counts = {};
    this.scene.traverse((o) => { if (o.userData.rtk) counts[o.userData.rtk] = (counts[o.userData.rtk] || 0) + 1; });
    return counts;
  }
}
