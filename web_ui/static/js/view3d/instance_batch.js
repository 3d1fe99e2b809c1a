// Many opaque copies of one shape, each with its own matrix and colour, drawn in one draw call
// (a three.js InstancedMesh): 500 cube markers cost one draw, not 500. Slots are keyed; removing
// one moves the last into its place, so the batch stays packed.

import * as THREE from "three";

const INITIAL_CAPACITY = 64;

export class InstanceBatch {
  constructor(geometry) {
    this.geometry = geometry;
    this.material = new THREE.MeshLambertMaterial();
    this.keys = []; // slot -> key
    this._slots = new Map(); // key -> slot
    this.mesh = this._newMesh(INITIAL_CAPACITY);
    this._dirty = false;
  }

  _newMesh(capacity) {
    const mesh = new THREE.InstancedMesh(this.geometry, this.material, capacity);
    mesh.count = 0;
    mesh.frustumCulled = false; // instances anywhere: no bounding sphere to keep
    mesh.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
    mesh.setColorAt(0, new THREE.Color()); // makes the per-instance colour buffer
    return mesh;
  }

  get size() {
    return this.keys.length;
  }

  has(key) {
    return this._slots.has(key);
  }

  /** Put `key` at `matrix` (fixed frame, scale included) in `color`; grows when full. */
  set(key, matrix, color) {
    let slot = this._slots.get(key);
    if (slot === undefined) {
      slot = this.keys.length;
      if (slot >= this.mesh.instanceMatrix.count) this._grow();
      this.keys.push(key);
      this._slots.set(key, slot);
      this.mesh.count = this.keys.length;
    }
    this.mesh.setMatrixAt(slot, matrix);
    this.mesh.setColorAt(slot, color);
    this._dirty = true;
  }

  remove(key) {
    const slot = this._slots.get(key);
    if (slot === undefined) return;
    const last = this.keys.length - 1;
    if (slot !== last) {
      const moved = this.keys[last];
      this.mesh.setMatrixAt(slot, this.mesh.getMatrixAt(last, _matrix));
      this.mesh.setColorAt(slot, this.mesh.getColorAt(last, _color));
      this.keys[slot] = moved;
      this._slots.set(moved, slot);
    }
    this.keys.pop();
    this._slots.delete(key);
    this.mesh.count = this.keys.length;
    this._dirty = true;
  }

  /** The fixed-frame position of `key`, or null. */
  positionOf(key) {
    const slot = this._slots.get(key);
    if (slot === undefined) return null;
    return new THREE.Vector3().setFromMatrixPosition(this.mesh.getMatrixAt(slot, _matrix));
  }

  /** Upload what changed since the last frame. */
  flush() {
    if (!this._dirty) return;
    this.mesh.instanceMatrix.needsUpdate = true;
    this.mesh.instanceColor.needsUpdate = true;
    this._dirty = false;
  }

  _grow() {
    const old = this.mesh;
    const mesh = this._newMesh(old.instanceMatrix.count * 2);
    mesh.instanceMatrix.array.set(old.instanceMatrix.array);
    mesh.instanceColor.array.set(old.instanceColor.array);
    mesh.count = old.count;
    const parent = old.parent;
    if (parent) parent.add(mesh);
    old.removeFromParent();
    old.dispose();
    this.mesh = mesh;
  }

  dispose() {
    this.mesh.removeFromParent();
    this.mesh.dispose();
    this.material.dispose();
  }
}

const _matrix = new THREE.Matrix4();
const _color = new THREE.Color();
