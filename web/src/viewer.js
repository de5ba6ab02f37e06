// The three.js view: one mesh per shown method (side by side along x), vertex colours for the selection or
// the energy map, optional input-edge wireframe and intrinsic-edge overlay, an orbit camera and one gizmo
// (TransformControls) per copy on its handle. Positions live in each view's BufferGeometry: what is
// displayed.
//
// The handle's motion is one affine map M in mesh coordinates, shared by the copies (the server applies it
// to every method's anchors). Copy k shows its gizmo at T(o_k) M P_k, with o_k the copy's offset and P_k
// the pivot (mesh coordinates) placed on its handle; dragging copy j's gizmo to G gives M = T(-o_j) G
// P_j^-1, and the other gizmos follow.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { TransformControls } from 'three/addons/controls/TransformControls.js';
import { NO_GROUP, groupColor } from './rigid_groups.js';
import { checkerTexture } from './uv_layout.js';

const baseColor = [0.72, 0.74, 0.78];
const fixedColor = [0.9, 0.16, 0.16];
const handleColor = [1.0, 0.76, 0.15];
const softHandleColor = [1.0, 0.91, 0.66];
const targetColor = 0xd070ff;

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
    this.pivot = new THREE.Matrix4(); // where the gizmo sits while M is the identity (mesh coordinates)
    this.wire = new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({ color: 0x111111, wireframe: true, transparent: true, opacity: 0.35 }));
    this.wire.position.copy(offset);
    this.wire.visible = false;
    this.intrinsic = null;
    this.targetPoints = null; // the fit's target (Viewer.setTarget)
    this.atlas = null; // the UV tab's atlas drawn on the faces' own corners (setAtlas)
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
    if (this.atlas) this.#spreadToCorners(this.atlas.geometry);
  }

  // The shared geometry's positions and smooth normals copied to each face's own three corners.
  #spreadToCorners(cornerGeometry) {
    const index = this.mesh.geometry.index.array;
    const { position, normal } = this.mesh.geometry.attributes;
    const cornerPosition = cornerGeometry.attributes.position;
    const cornerNormal = cornerGeometry.attributes.normal;
    for (let c = 0; c < index.length; ++c) {
      for (let k = 0; k < 3; ++k) {
        cornerPosition.array[3 * c + k] = position.array[3 * index[c] + k];
        cornerNormal.array[3 * c + k] = normal.array[3 * index[c] + k];
      }
    }
    cornerPosition.needsUpdate = cornerNormal.needsUpdate = true;
    cornerGeometry.computeBoundingSphere();
  }

  // The atlas's corner colours: a vertex's selection colour (selectionColor(v), null for none) on the
  // corners of selected vertices, so that painting stays visible, its chart's colour on the others.
  paintAtlas(selectionColor) {
    if (!this.atlas) return;
    const index = this.mesh.geometry.index.array;
    const color = this.atlas.geometry.attributes.color;
    for (let c = 0; c < index.length; ++c) {
      const own = selectionColor ? selectionColor(index[c]) : null;
      for (let k = 0; k < 3; ++k) color.array[3 * c + k] = own ? own[k] : this.chartColors[3 * c + k];
    }
    color.needsUpdate = true;
  }

  // An atlas on this copy ({checker, colors} per corner, uv_layout.js's atlasCornerArrays), or none (null).
  // A UV per corner needs each face on its own three vertices: a second mesh of the same surface is drawn
  // instead of the shared one, which stays for picking (its material hidden) and keeps the wireframe.
  setAtlas(atlas, texture) {
    if (this.atlas) {
      this.mesh.remove(this.atlas);
      this.atlas.geometry.dispose();
      this.atlas.material.dispose();
      this.atlas = null;
    }
    this.mesh.material.visible = !atlas;
    if (!atlas) return;
    const corners = this.mesh.geometry.index.count;
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3 * corners), 3));
    geometry.setAttribute('normal', new THREE.BufferAttribute(new Float32Array(3 * corners), 3));
    geometry.setAttribute('uv', new THREE.BufferAttribute(atlas.checker, 2));
    geometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(atlas.colors), 3)); // painted per copy
    this.chartColors = atlas.colors;
    this.#spreadToCorners(geometry);
    const { polygonOffset, polygonOffsetFactor, polygonOffsetUnits } = this.mesh.material;
    this.atlas = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({
      vertexColors: true, map: texture, roughness: 0.75, metalness: 0.0, side: THREE.DoubleSide,
      polygonOffset, polygonOffsetFactor, polygonOffsetUnits,
    }));
    this.atlas.raycast = () => {}; // picking goes to the shared mesh
    this.mesh.add(this.atlas); // follows the copy's offset
  }

  // The checkerboard on this copy (checker: Float32Array #V x 2 in checker units), or none (null).
  setTexture(checker, texture) {
    const { geometry, material } = this.mesh;
    if (checker) geometry.setAttribute('uv', new THREE.BufferAttribute(checker, 2));
    else geometry.deleteAttribute('uv');
    material.map = checker ? texture : null;
    material.needsUpdate = true;
  }

  dispose(scene) {
    if (this.gizmo) {
      this.gizmo.detach();
      scene.remove(this.gizmo.getHelper(), this.gizmoTarget);
      this.gizmo.dispose();
    }
    scene.remove(this.mesh, this.wire);
    if (this.intrinsic) scene.remove(this.intrinsic);
    if (this.targetPoints) scene.remove(this.targetPoints);
    this.setAtlas(null);
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

    // Gizmos are made per copy (setLayout) before the orbit controls listen, so that selection tools can
    // see that a pointer press went to a gizmo.
    this.orbit = null;
    this.gizmoMode = 'translate';
    this.handleMatrix = new THREE.Matrix4(); // M
    this.handleIndices = [];
    this.gizmoListeners = { change: [], dragEnd: [] };

    this.views = [];
    this.softHandle = false;
    this.targetGeometry = null; // the fit's target points, drawn beside every copy
    this.targetVisible = true;
    this.faces = null;
    this.rest = null;
    this.overlay = null;
    this.#buildGizmos();
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  // Frames are drawn on demand (a change of the camera, a gizmo, positions or colours), not in a loop: a
  // still view then costs nothing, which matters with software WebGL and beside the solver.
  requestRender() {
    if (this.renderQueued) return;
    this.renderQueued = true;
    requestAnimationFrame(() => {
      this.renderQueued = false;
      this.render();
    });
  }

  resize() {
    const { clientWidth: w, clientHeight: h } = this.container;
    if (w === 0 || h === 0) return;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.requestRender();
  }

  render() {
    this.renderer.render(this.scene, this.camera);
    this.#placeLabels();
  }

  // A new mesh: faces Uint32Array (#F x 3), rest Float32Array (#V x 3); shows the given methods.
  setMesh(faces, rest, methods) {
    this.faces = faces;
    this.rest = rest;
    this.overlay = null;
    this.checker = null;
    this.atlas = null;
    this.selectionColor = null; // the next paint() sets it for this mesh's labels
    this.handleIndices = [];
    this.handleMatrix.identity();
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
    for (const view of this.views) view.dispose(this.scene);
    const spacing = this.size.x + 0.25 * this.diagonal;
    this.views = methods.map((method, i) => {
      const view = new MethodView(method, this.faces, positions?.[method] ?? this.rest, new THREE.Vector3((i - (methods.length - 1) / 2) * spacing, 0, 0));
      view.wire.visible = wireVisible;
      this.scene.add(view.mesh, view.wire);
      return view;
    });
    this.#buildGizmos();
    this.#buildLabels();
    this.#buildTargetPoints();
    if (this.overlay) this.setIntrinsicOverlay(this.overlay);
    if (this.checker) this.setTexture(this.checker);
    if (this.atlas) this.setAtlas(this.atlas);
    this.requestRender();
  }

  // The UV tab's checkerboard on every copy (checker: Float32Array #V x 2 in checker units, see
  // uv_layout.js), kept across layouts until a new mesh or null.
  setTexture(checker) {
    this.checker = checker;
    this.checkerTexture ??= checkerTexture();
    for (const view of this.views) view.setTexture(checker, this.checkerTexture);
    this.requestRender();
  }

  // The UV tab's atlas on every copy (atlas: {checker, colors} per corner, see uv_layout.js's
  // atlasCornerArrays, checker coordinates tiling the same texture), kept across layouts until a new mesh
  // or null.
  setAtlas(atlas) {
    this.atlas = atlas;
    this.checkerTexture ??= checkerTexture();
    for (const view of this.views) {
      view.setAtlas(atlas, this.checkerTexture);
      view.paintAtlas(this.selectionColor);
    }
    this.requestRender();
  }

  hasAtlas() {
    return this.views.length > 0 && this.views.every((view) => view.atlas !== null);
  }

  hasTexture() {
    return this.views.length > 0 && this.views.every((view) => view.mesh.material.map !== null);
  }

  // A gizmo per copy, then the orbit controls (pointer listeners run in the order they were added).
  #buildGizmos() {
    const orbitState = this.orbit ? { target: this.orbit.target.clone(), buttons: { ...this.orbit.mouseButtons } } : null;
    this.orbit?.dispose();
    for (const view of this.views) {
      view.gizmoTarget = new THREE.Object3D();
      view.gizmo = new TransformControls(this.camera, this.renderer.domElement);
      view.gizmo.setSize(0.9);
      view.gizmo.setMode(this.gizmoMode);
      view.gizmo.addEventListener('change', () => this.requestRender());
      view.gizmo.addEventListener('dragging-changed', (event) => {
        this.orbit.enabled = !event.value;
        if (!event.value) for (const listener of this.gizmoListeners.dragEnd) listener();
      });
      view.gizmo.addEventListener('objectChange', () => {
        if (!view.gizmo.dragging) return; // moves made by #showGizmos, not by the user
        view.gizmoTarget.updateMatrix();
        const o = view.offset;
        this.handleMatrix.makeTranslation(-o.x, -o.y, -o.z).multiply(view.gizmoTarget.matrix).multiply(view.pivot.clone().invert());
        this.#showGizmos(view);
        for (const listener of this.gizmoListeners.change) listener();
      });
      this.scene.add(view.gizmoTarget, view.gizmo.getHelper());
    }
    this.orbit = new OrbitControls(this.camera, this.renderer.domElement);
    this.orbit.enableDamping = false;
    this.orbit.addEventListener('change', () => this.requestRender());
    if (orbitState) {
      this.orbit.target.copy(orbitState.target);
      Object.assign(this.orbit.mouseButtons, orbitState.buttons);
    }
    this.placeGizmo(this.handleIndices, false);
  }

  // Every gizmo but `except` moved to show M.
  #showGizmos(except = null) {
    for (const view of this.views) {
      if (view === except || !view.gizmoTarget) continue;
      const o = view.offset;
      const m = new THREE.Matrix4().makeTranslation(o.x, o.y, o.z).multiply(this.handleMatrix).multiply(view.pivot);
      m.decompose(view.gizmoTarget.position, view.gizmoTarget.quaternion, view.gizmoTarget.scale);
      view.gizmoTarget.updateMatrix();
    }
    this.requestRender();
  }

  onGizmoChange(listener) {
    this.gizmoListeners.change.push(listener);
  }

  onGizmoDragEnd(listener) {
    this.gizmoListeners.dragEnd.push(listener);
  }

  setGizmoMode(mode) {
    this.gizmoMode = mode;
    for (const view of this.views) view.gizmo?.setMode(mode);
  }

  // Whether a gizmo is hovered or dragged (a press then belongs to it, not to a selection tool).
  gizmoActive() {
    return this.views.some((v) => v.gizmo && (v.gizmo.dragging || v.gizmo.axis !== null));
  }

  // Fits every copy in the window: the camera backs off until both the height and the width of the row
  // of copies fit the field of view.
  fitCamera() {
    const spread = (this.views.length - 1) * (this.size.x + 0.25 * this.diagonal);
    const halfWidth = 0.5 * (spread + this.size.x) + 0.15 * this.diagonal;
    const halfHeight = 0.5 * this.size.y + 0.15 * this.diagonal;
    const tanHalf = Math.tan((Math.PI * this.camera.fov) / 360);
    const distance = Math.max(halfHeight / tanHalf, halfWidth / (tanHalf * this.camera.aspect)) + 0.5 * this.size.z;
    this.orbit.target.copy(this.center);
    this.camera.near = distance * 1e-3;
    this.camera.far = distance * 100;
    this.camera.position.copy(this.center).add(new THREE.Vector3(0, 0.06 * distance, distance));
    this.camera.updateProjectionMatrix();
    this.orbit.update();
    this.requestRender();
  }

  view(method) {
    return this.views.find((v) => v.method === method);
  }

  // Vertex colours from the selection labels (0 free, 1 fixed, 2 handle, paler when soft), then the rigid
  // groups' colours (groups: per vertex, NO_GROUP for none), or energy colours for the rest.
  paint(labels, energyColorsByMethod, groups = null) {
    const handle = this.softHandle ? softHandleColor : handleColor;
    // A vertex's selection or group colour, null for none; kept for an atlas drawn later (setAtlas).
    this.selectionColor = (i) => {
      const group = groups ? groups[i] : NO_GROUP;
      return labels[i] === 1 ? fixedColor : labels[i] === 2 ? handle : group !== NO_GROUP ? groupColor(group) : null;
    };
    for (const view of this.views) {
      const colors = view.mesh.geometry.attributes.color.array;
      const energy = energyColorsByMethod?.[view.method];
      for (let i = 0; i < labels.length; ++i) {
        const c = this.selectionColor(i);
        for (let k = 0; k < 3; ++k) colors[3 * i + k] = c ? c[k] : energy ? energy[3 * i + k] : baseColor[k];
      }
      view.mesh.geometry.attributes.color.needsUpdate = true;
      view.paintAtlas(this.selectionColor);
    }
    this.requestRender();
  }

  // Whether the handle is soft (painted paler by the next paint()).
  setSoftHandle(soft) {
    this.softHandle = soft;
  }

  // The fit's target (points: Float32Array #P x 3 in mesh coordinates) drawn as points beside every copy,
  // or none (null).
  setTarget(points) {
    this.targetGeometry?.dispose();
    this.targetGeometry = null;
    if (points) {
      this.targetGeometry = new THREE.BufferGeometry();
      this.targetGeometry.setAttribute('position', new THREE.BufferAttribute(points, 3));
      this.targetGeometry.computeBoundingSphere();
    }
    this.#buildTargetPoints();
  }

  setTargetVisible(visible) {
    this.targetVisible = visible;
    for (const view of this.views) if (view.targetPoints) view.targetPoints.visible = visible;
    this.requestRender();
  }

  #buildTargetPoints() {
    for (const view of this.views) {
      if (view.targetPoints) this.scene.remove(view.targetPoints);
      view.targetPoints = null;
      if (!this.targetGeometry) continue;
      // A few pixels whatever the distance: a scan's points stay visible from afar and do not hide the mesh.
      view.targetPoints = new THREE.Points(this.targetGeometry, new THREE.PointsMaterial({ color: targetColor, size: 2.5, sizeAttenuation: false }));
      view.targetPoints.position.copy(view.offset);
      view.targetPoints.visible = this.targetVisible;
      this.scene.add(view.targetPoints);
    }
    this.requestRender();
  }

  setWireframe(visible) {
    for (const view of this.views) view.wire.visible = visible;
    this.requestRender();
  }

  // overlay: decoded /api/intrinsic_edges frame; null hides it.
  setIntrinsicOverlay(overlay) {
    this.overlay = overlay;
    this.requestRender();
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
    this.requestRender();
  }

  setPositions(method, positions) {
    const view = this.view(method);
    if (!view) return;
    view.setPositions(positions);
    this.#updateIntrinsic(view);
    this.requestRender();
  }

  // Puts each copy's gizmo, with identity rotation, at the centroid of the handle in that copy and, when
  // resetMatrix, makes M the identity (the server's anchors were just re-taken). Otherwise (a copy shown
  // anew) the pivot is the handle's centroid taken back through M, so that the gizmo shows on the handle.
  placeGizmo(handle, resetMatrix = true) {
    this.handleIndices = handle;
    if (resetMatrix) this.handleMatrix.identity();
    const back = this.handleMatrix.clone().invert();
    for (const view of this.views) {
      if (!view.gizmo) continue;
      if (handle.length === 0) {
        view.gizmo.detach();
        continue;
      }
      const X = view.positions();
      const centroid = new THREE.Vector3();
      for (const i of handle) centroid.add(new THREE.Vector3(X[3 * i], X[3 * i + 1], X[3 * i + 2]));
      centroid.divideScalar(handle.length).applyMatrix4(back);
      view.pivot.makeTranslation(centroid.x, centroid.y, centroid.z);
      view.gizmo.attach(view.gizmoTarget);
    }
    this.#showGizmos();
  }

  // The handle's affine map M in mesh coordinates, as 16 column-major numbers.
  handleTransform() {
    return Array.from(this.handleMatrix.elements);
  }

  // Gizmo state for undo: M and each copy's pivot.
  gizmoState() {
    return { matrix: this.handleTransform(), pivots: Object.fromEntries(this.views.map((v) => [v.method, Array.from(v.pivot.elements)])) };
  }

  setGizmoState(state) {
    this.handleMatrix.fromArray(state.matrix);
    for (const view of this.views) if (state.pivots[view.method]) view.pivot.fromArray(state.pivots[view.method]);
    this.#showGizmos();
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

  // The index of the copy whose screen box holds the client point, else the nearest copy's.
  viewAt(clientX, clientY) {
    let best = 0, bestDistance = Infinity;
    this.views.forEach((view, index) => {
      const box = this.screenBox(index);
      const dx = Math.max(box.x0 - clientX, 0, clientX - box.x1);
      const dy = Math.max(box.y0 - clientY, 0, clientY - box.y1);
      if (Math.hypot(dx, dy) < bestDistance) {
        best = index;
        bestDistance = Math.hypot(dx, dy);
      }
    });
    return best;
  }

  // Client-pixel bounding box of the corners of copy `index`'s bounding box.
  screenBox(index) {
    const geometry = this.views[index].mesh.geometry;
    geometry.computeBoundingBox();
    const { min, max } = geometry.boundingBox;
    const corners = [];
    for (const x of [min.x, max.x]) for (const y of [min.y, max.y]) for (const z of [min.z, max.z]) corners.push(this.toScreen(new THREE.Vector3(x, y, z), index));
    return { x0: Math.min(...corners.map((c) => c.x)), x1: Math.max(...corners.map((c) => c.x)), y0: Math.min(...corners.map((c) => c.y)), y1: Math.max(...corners.map((c) => c.y)) };
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
