// The shapes the 3D view draws with: unit geometries shared by every object that uses them
// (scaled per object, never rebuilt per message), axes, and text that always faces the camera.

import * as THREE from "three";

let unit = null;

/** Shared unit geometries: box and sphere 1 m across, cylinder 1 m across and tall along z,
 * arrow 1 m long along +x (head 1 m across, shaft half that, head 23% of the length, as rviz). */
export function unitGeometry() {
  if (unit) return unit;
  const cylinder = new THREE.CylinderGeometry(0.5, 0.5, 1, 24).rotateX(Math.PI / 2);
  const arrowProfile = [
    new THREE.Vector2(0, 0),
    new THREE.Vector2(0.25, 0),
    new THREE.Vector2(0.25, 0.77),
    new THREE.Vector2(0.5, 0.77),
    new THREE.Vector2(0, 1),
  ];
  unit = {
    box: new THREE.BoxGeometry(1, 1, 1),
    sphere: new THREE.SphereGeometry(0.5, 20, 14),
    cylinder,
    arrow: new THREE.LatheGeometry(arrowProfile, 20).rotateZ(-Math.PI / 2),
    shaft: new THREE.CylinderGeometry(0.5, 0.5, 1, 16).rotateZ(-Math.PI / 2).translate(0.5, 0, 0),
    cone: new THREE.ConeGeometry(0.5, 1, 20).rotateZ(-Math.PI / 2).translate(0.5, 0, 0),
  };
  return unit;
}

/**
 * Set `object`'s scale to `factor` along the axes `axes` marks with 1 (others stay 1); true if it
 * changed by more than 1 % (a model kept a few pixels across: no redraw for less).
 */
export function fitScale(object, factor, axes) {
  const wanted = axes.map((on) => (on ? factor : 1));
  const current = object.scale.toArray();
  if (wanted.every((w, i) => Math.abs(w - current[i]) <= 0.01 * current[i])) return false;
  object.scale.fromArray(wanted);
  return true;
}

export function solidMaterial(color, opacity = 1) {
  return new THREE.MeshLambertMaterial({ color, transparent: opacity < 1, opacity, depthWrite: opacity >= 1 });
}

const AXIS_COLORS = [0xe0434b, 0x47c04a, 0x3d7ff0];

/** x, y, z axes as red, green, blue rods of `length`, as rviz's Axes. */
export function makeAxes(length, radius) {
  const group = new THREE.Group();
  const { cylinder } = unitGeometry();
  const rotations = [
    new THREE.Euler(0, Math.PI / 2, 0), // z -> x
    new THREE.Euler(-Math.PI / 2, 0, 0), // z -> y
    new THREE.Euler(0, 0, 0),
  ];
  const offsets = [
    new THREE.Vector3(length / 2, 0, 0),
    new THREE.Vector3(0, length / 2, 0),
    new THREE.Vector3(0, 0, length / 2),
  ];
  for (let axis = 0; axis < 3; axis++) {
    const rod = new THREE.Mesh(cylinder, solidMaterial(AXIS_COLORS[axis]));
    rod.rotation.copy(rotations[axis]);
    rod.position.copy(offsets[axis]);
    rod.scale.set(radius * 2, radius * 2, length);
    group.add(rod);
  }
  return group;
}

/** Dispose what `object` owns: materials and textures always, geometries unless shared. */
export function disposeObject(object) {
  const shared = new Set(unit ? Object.values(unit) : []);
  object.traverse((child) => {
    if (child.geometry && !shared.has(child.geometry)) child.geometry.dispose();
    const materials = Array.isArray(child.material) ? child.material : child.material ? [child.material] : [];
    for (const material of materials) {
      if (material.map) material.map.dispose();
      material.dispose();
    }
  });
}

const TEXT_PX = 48; // canvas pixels per text line: sharp enough at any zoom the view allows

/** A sprite showing `text`, `height` metres tall, always facing the camera. */
export function textSprite(text, color = "#ffffff", height = 0.2) {
  const sprite = new THREE.Sprite(new THREE.SpriteMaterial({ transparent: true, depthWrite: false }));
  setSpriteText(sprite, text, color, height);
  return sprite;
}

/** Redraw a text sprite only when its text or colour changed; rescale always. */
export function setSpriteText(sprite, text, color, height) {
  const key = `${color}\u0000${text}`;
  if (sprite.userData.textKey !== key) {
    const canvas = document.createElement("canvas");
    const ctx = canvas.getContext("2d");
    const font = `600 ${TEXT_PX}px system-ui, sans-serif`;
    ctx.font = font;
    const lines = String(text).split("\n");
    const width = Math.max(1, ...lines.map((line) => ctx.measureText(line).width));
    canvas.width = Math.ceil(width + TEXT_PX * 0.4);
    canvas.height = Math.ceil(TEXT_PX * 1.25 * lines.length);
    ctx.font = font;
    ctx.textAlign = "center";
    ctx.textBaseline = "middle";
    ctx.lineWidth = TEXT_PX * 0.12;
    ctx.strokeStyle = "rgba(0, 0, 0, 0.75)";
    ctx.fillStyle = color;
    lines.forEach((line, i) => {
      const y = TEXT_PX * 1.25 * (i + 0.5);
      ctx.strokeText(line, canvas.width / 2, y);
      ctx.fillText(line, canvas.width / 2, y);
    });
    if (sprite.material.map) sprite.material.map.dispose();
    const texture = new THREE.CanvasTexture(canvas);
    texture.colorSpace = THREE.SRGBColorSpace;
    sprite.material.map = texture;
    sprite.material.needsUpdate = true;
    sprite.userData.textKey = key;
    sprite.userData.aspect = canvas.width / canvas.height;
    sprite.userData.lines = lines.length;
  }
  const lineHeight = height * sprite.userData.lines;
  sprite.scale.set(lineHeight * sprite.userData.aspect, lineHeight, 1);
}
