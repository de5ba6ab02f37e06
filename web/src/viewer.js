// The three.js view: one mesh per shown method (side by side along x), vertex colours for the selection or
// the energy map, optional input-edge wireframe and intrinsic-edge overlay, an orbit camera and a gizmo
// (TransformControls) on the handle. Positions live in each view's BufferGeometry: what is displayed.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { TransformControls } from 'three/addons/controls/TransformControls.js';

const baseColor = [0.72, 0.74, 0.78];
const fixedColor = [0.9, 0.16, 0.16];
const handleColor = [1.0, 0.76, 0.15];

class MethodView {
  constructor(method, faces, rest, offset) {
    this.method = method;
    this.offset = offset;
    const geometry = new THREE.BufferGeometry();
    geometry.setIndex(new THREE.BufferAttribute(faces, 1));
    geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(rest), 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(rest.length), 3));
    geometry.computeVertexNormals();
    this.mesh = new THREE.Mesh(
      geometry,
      new THREE.MeshStandardMaterial({
        vertexColors: true, roughness: 0.75, metalness: 0.0, side: THREE.DoubleSide,
        polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
      }),
    );
    this.mesh.position.copy(offset);
    this.wire = new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({ color: 0x111111, wireframe: true, transparent: true, opacity: 0.35 }));
    this.wire.position.copy(offset);
    this.wire.visible = false;
    this.intrinsic = null;
  }

  positions() {
    return this.mesh.geometry.attributes.position.array;
  }

  setPositions(positions) {
    const attribute = this.mesh.geometry.attributes.position;
    attribute.array.set(positions);
    attribute.needsUpdate = true;
    this.mesh.geometry.computeVertexNormals();
    this.mesh.geometry.computeBoundingSphere();
    this.mesh.geometry.computeBoundingBox();
  }

  dispose(scene) {
    scene.remove(this.mesh, this.wire);
    if (this.intrinsic) scene.remove(this.intrinsic);
    this.mesh.geometry.dispose();
    this.intrinsic?.geometry.dispose();
  }
}

export class Viewer {
  constructor(container, labels) {
    this.container = container;
    this.labels = labels;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio);
    this.renderer.setClearColor(0x1c1f24);
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(40, 1, 1e-3, 1e3);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x445566, 1.6));
    const light = new THREE.DirectionalLight(0xffffff, 1.6);
    light.position.set(1, 2, 3);
    this.camera.add(light);
    this.scene.add(this.camera);

    // The gizmo listens first, so selection tools can see that a pointer press went to it.
    this.gizmoTarget = new THREE.Object3D();
    this.scene.add(this.gizmoTarget);
    this.gizmo = new TransformControls(this.camera, this.renderer.domElement);
    this.gizmo.setSize(0.9);
    this.scene.add(this.gizmo.getHelper());
    this.orbit = new OrbitControls(this.camera, this.renderer.domElement);
    this.orbit.enableDamping = false;
    this.gizmo.addEventListener('dragging-changed', (event) => { this.orbit.enabled = !event.value; });

    this.views = [];
    this.faces = null;
    this.rest = null;
    this.anchorMatrix = new THREE.Matrix4();
    this.overlay = null;
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
    this.renderer.setAnimationLoop(() => this.render());
  }

  resize() {
    const { clientWidth: w, clientHeight: h } = this.container;
    if (w === 0 || h === 0) return;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
  }

  render() {
    this.orbit.update();
    this.renderer.render(this.scene, this.camera);
    this.#placeLabels();
  }

  // A new mesh: faces Uint32Array (#F x 3), rest Float32Array (#V x 3); shows the given methods.
  setMesh(faces, rest, methods) {
    this.faces = faces;
    this.rest = rest;
    this.overlay = null;
    const box = new THREE.Box3().setFromArray(rest);
    this.center = box.getCenter(new THREE.Vector3());
    this.size = box.getSize(new THREE.Vector3());
    this.diagonal = this.size.length();
    this.setLayout(methods, null);
    this.fitCamera();
  }

  // One view per method, spaced along x; positions: {method: Float32Array} or null for the rest shape.
  setLayout(methods, positions) {
    const wireVisible = this.views[0]?.wire.visible ?? false;
    const oldOffset = this.views[0]?.offset.clone() ?? new THREE.Vector3();
    for (const view of this.views) view.dispose(this.scene);
    const spacing = this.size.x + 0.25 * this.diagonal;
    this.views = methods.map((method, i) => {
      const view = new MethodView(method, this.faces, positions?.[method] ?? this.rest, new THREE.Vector3((i - (methods.length - 1) / 2) * spacing, 0, 0));
      view.wire.visible = wireVisible;
      this.scene.add(view.mesh, view.wire);
      return view;
    });
    // The gizmo and its anchor live in view 0's frame; follow that view to its new place.
    const shift = this.views[0].offset.clone().sub(oldOffset);
    this.gizmoTarget.position.add(shift);
    this.anchorMatrix.premultiply(new THREE.Matrix4().makeTranslation(shift.x, shift.y, shift.z));
    this.#buildLabels();
    if (this.overlay) this.setIntrinsicOverlay(this.overlay);
  }

  fitCamera() {
    const spread = (this.views.length - 1) * (this.size.x + 0.25 * this.diagonal);
    const radius = 0.5 * Math.max(this.diagonal, spread + this.size.x);
    this.orbit.target.copy(this.center);
    this.camera.near = radius * 1e-3;
    this.camera.far = radius * 100;
    this.camera.position.copy(this.center).add(new THREE.Vector3(0, 0.15 * radius, 2.6 * radius));
    this.camera.updateProjectionMatrix();
    this.orbit.update();
  }

  view(method) {
    return this.views.find((v) => v.method === method);
  }

  // Vertex colours from the selection labels (0 free, 1 fixed, 2 handle), or energy colours for free ones.
  paint(labels, energyColorsByMethod) {
    for (const view of this.views) {
      const colors = view.mesh.geometry.attributes.color.array;
      const energy = energyColorsByMethod?.[view.method];
      for (let i = 0; i < labels.length; ++i) {
        const c = labels[i] === 1 ? fixedColor : labels[i] === 2 ? handleColor : null;
        for (let k = 0; k < 3; ++k) colors[3 * i + k] = c ? c[k] : energy ? energy[3 * i + k] : baseColor[k];
      }
      view.mesh.geometry.attributes.color.needsUpdate = true;
    }
  }

  setWireframe(visible) {
    for (const view of this.views) view.wire.visible = visible;
  }

  // overlay: decoded /api/intrinsic_edges frame; null hides it.
  setIntrinsicOverlay(overlay) {
    this.overlay = overlay;
    for (const view of this.views) {
      if (view.intrinsic) {
        this.scene.remove(view.intrinsic);
        view.intrinsic.geometry.dispose();
        view.intrinsic = null;
      }
      if (!overlay) continue;
      const { start, a, c, t, original } = overlay.arrays;
      let segments = 0;
      for (let e = 0; e + 1 < start.length; ++e) segments += start[e + 1] - start[e] - 1;
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(6 * segments), 3));
      const colors = new Float32Array(6 * segments);
      // Endpoint j of segment s is point p = ends[2s + j] of the traces.
      const ends = new Int32Array(2 * segments);
      let s = 0;
      for (let e = 0; e + 1 < start.length; ++e) {
        // Input edges kept by the flips stay discreet; the flipped-in edges (Fig. 14) stand out.
        const color = original[e] ? [0.3, 0.32, 0.36] : [0.1, 0.9, 1.0];
        for (let p = start[e]; p + 1 < start[e + 1]; ++p, ++s) {
          ends[2 * s] = p;
          ends[2 * s + 1] = p + 1;
          colors.set(color, 6 * s);
          colors.set(color, 6 * s + 3);
        }
      }
      geometry.setAttribute('color', new THREE.BufferAttribute(colors, 3));
      view.intrinsic = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ vertexColors: true }));
      view.intrinsic.userData = { ends, a, c, t };
      view.intrinsic.position.copy(view.offset);
      this.scene.add(view.intrinsic);
      this.#updateIntrinsic(view);
    }
  }

  #updateIntrinsic(view) {
    if (!view.intrinsic) return;
    const { ends, a, c, t } = view.intrinsic.userData;
    const X = view.positions();
    const out = view.intrinsic.geometry.attributes.position;
    for (let j = 0; j < ends.length; ++j) {
      const p = ends[j];
      const u = c[p] < 0 ? 0 : t[p];
      const ia = 3 * a[p];
      const ic = 3 * (c[p] < 0 ? a[p] : c[p]);
      for (let k = 0; k < 3; ++k) out.array[3 * j + k] = (1 - u) * X[ia + k] + u * X[ic + k];
    }
    out.needsUpdate = true;
    view.intrinsic.geometry.computeBoundingSphere();
  }

  setPositions(method, positions) {
    const view = this.view(method);
    if (!view) return;
    view.setPositions(positions);
    this.#updateIntrinsic(view);
  }

  // Puts the gizmo, with identity rotation, at the centroid of the handle in view 0 and records that
  // placement: handle transforms are measured from it (the server's anchors).
  placeGizmo(handle) {
    if (handle.length === 0 || this.views.length === 0) {
      this.gizmo.detach();
      return;
    }
    const X = this.views[0].positions();
    const centroid = new THREE.Vector3();
    for (const i of handle) centroid.add(new THREE.Vector3(X[3 * i], X[3 * i + 1], X[3 * i + 2]));
    centroid.divideScalar(handle.length).add(this.views[0].offset);
    this.gizmoTarget.position.copy(centroid);
    this.gizmoTarget.quaternion.identity();
    this.gizmoTarget.scale.set(1, 1, 1);
    this.gizmoTarget.updateMatrix();
    this.anchorMatrix.copy(this.gizmoTarget.matrix);
    this.gizmo.attach(this.gizmoTarget);
  }

  // The handle's affine map since placeGizmo, in mesh coordinates, as 16 column-major numbers.
  handleTransform() {
    this.gizmoTarget.updateMatrix();
    const offset = this.views[0]?.offset ?? new THREE.Vector3();
    const toMesh = new THREE.Matrix4().makeTranslation(offset.x, offset.y, offset.z);
    const relative = new THREE.Matrix4().copy(this.gizmoTarget.matrix).multiply(this.anchorMatrix.clone().invert());
    const m = new THREE.Matrix4().copy(toMesh).invert().multiply(relative).multiply(toMesh);
    return Array.from(m.elements);
  }

  // Client-pixel position of a point of view `index` given in mesh coordinates.
  toScreen(point, index = 0) {
    const rect = this.renderer.domElement.getBoundingClientRect();
    const p = point.clone().add(this.views[index].offset).project(this.camera);
    return { x: rect.left + (0.5 + 0.5 * p.x) * rect.width, y: rect.top + (0.5 - 0.5 * p.y) * rect.height, z: p.z };
  }

  // Raycasts the shown meshes; returns {view, point (mesh coordinates)} or null.
  pick(clientX, clientY) {
    const rect = this.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(((clientX - rect.left) / rect.width) * 2 - 1, -((clientY - rect.top) / rect.height) * 2 + 1);
    const raycaster = new THREE.Raycaster();
    raycaster.setFromCamera(ndc, this.camera);
    const hits = raycaster.intersectObjects(this.views.map((v) => v.mesh), false);
    if (hits.length === 0) return null;
    const view = this.views.find((v) => v.mesh === hits[0].object);
    return { view, point: hits[0].point.clone().sub(view.offset) };
  }

  #buildLabels() {
    this.labels.replaceChildren(...this.views.map((v) => Object.assign(document.createElement('span'), { textContent: v.method })));
  }

  #placeLabels() {
    if (this.views.length < 2) {
      for (const span of this.labels.children) span.hidden = true;
      return;
    }
    const rect = this.renderer.domElement.getBoundingClientRect();
    this.views.forEach((view, i) => {
      const span = this.labels.children[i];
      const p = this.center.clone().add(view.offset).project(this.camera);
      span.hidden = false;
      span.style.left = `${(0.5 + 0.5 * p.x) * rect.width}px`;
    });
  }
}
