// A shaded figure from joint positions: a capsule-like cylinder per bone and a sphere per joint,
// casting shadows. Positions come flat per frame: [x0, y0, z0, x1, ...] in metres, y up.
// Planted foot joints (setPlanted) are drawn in PLANTED_COLOUR, with a disc of it on the floor.
import * as THREE from 'three';

const UP = new THREE.Vector3(0, 1, 0);
export const PLANTED_COLOUR = 0x17c964;
const JOINT_COLOUR = 0x3a4a5c;
const plantedMaterial = new THREE.MeshStandardMaterial({ color: PLANTED_COLOUR, roughness: 0.45 });
const discMaterial = new THREE.MeshBasicMaterial({ color: PLANTED_COLOUR, transparent: true, opacity: 0.75 });
const discGeometry = new THREE.CircleGeometry(0.075, 24).rotateX(-Math.PI / 2);

export class Figure {
  constructor(joints, color = 0xe07b39) {
    this.joints = joints;
    this.group = new THREE.Group();
    this.offset = new THREE.Vector3();
    const material = new THREE.MeshStandardMaterial({ color, roughness: 0.55, metalness: 0.05 });
    const jointMaterial = new THREE.MeshStandardMaterial({ color: JOINT_COLOUR, roughness: 0.6 });
    this.jointMaterial = jointMaterial;
    const boneGeometry = new THREE.CylinderGeometry(1, 1, 1, 10);
    const jointGeometry = new THREE.SphereGeometry(1, 12, 8);
    this.bones = [];
    this.spheres = [];
    joints.forEach((joint, j) => {
      const sphere = new THREE.Mesh(jointGeometry, jointMaterial);
      const radius = /head/i.test(joint.name) ? 0.11 : 0.035;
      sphere.scale.setScalar(radius);
      sphere.castShadow = true;
      this.group.add(sphere);
      this.spheres.push(sphere);
      if (joint.parent >= 0) {
        const bone = new THREE.Mesh(boneGeometry, material);
        bone.castShadow = true;
        bone.userData = { child: j, parent: joint.parent };
        this.group.add(bone);
        this.bones.push(bone);
      }
    });
    this.points = joints.map(() => new THREE.Vector3());
    this.discs = new Map();    // joint index -> its floor disc
    this.planted = new Set();  // joint indices drawn planted
  }

  // Marks joints `indices` planted where `flags` (0/1 each) say so, none when flags is null.
  // Call after setPose, so the discs go under the joints.
  setPlanted(indices, flags) {
    const on = new Set();
    if (indices && flags) indices.forEach((j, k) => { if (flags[k] && j >= 0 && j < this.spheres.length) on.add(j); });
    for (const j of new Set([...this.planted, ...on])) {
      const planted = on.has(j);
      const sphere = this.spheres[j];
      sphere.material = planted ? plantedMaterial : this.jointMaterial;
      sphere.scale.setScalar(planted ? 0.05 : 0.035);
      if (planted && !this.discs.has(j)) {
        const disc = new THREE.Mesh(discGeometry, discMaterial);
        this.group.add(disc);
        this.discs.set(j, disc);
      }
      if (this.discs.has(j)) this.discs.get(j).visible = planted;
    }
    for (const j of on) this.discs.get(j).position.set(this.points[j].x, 0.006, this.points[j].z);
    this.planted = on;
  }

  // What the marks show, for the browser test: per joint given, whether its sphere has the
  // planted colour and its disc is shown under it.
  plantedMarks(indices) {
    return indices.map((j) => {
      const disc = this.discs.get(j);
      return { joint: j, sphereColour: this.spheres[j].material.color.getHex(),
        disc: Boolean(disc && disc.visible && this.group.visible
          && Math.hypot(disc.position.x - this.points[j].x, disc.position.z - this.points[j].z) < 1e-6) };
    });
  }

  setPose(flat) {
    const p = this.points;
    for (let j = 0; j < p.length; ++j) {
      p[j].set(flat[3 * j], flat[3 * j + 1], flat[3 * j + 2]).add(this.offset);
      this.spheres[j].position.copy(p[j]);
    }
    const dir = new THREE.Vector3();
    for (const bone of this.bones) {
      const a = p[bone.userData.parent];
      const b = p[bone.userData.child];
      dir.subVectors(b, a);
      const length = dir.length();
      bone.visible = length > 1e-3;
      if (!bone.visible) continue;
      bone.position.addVectors(a, b).multiplyScalar(0.5);
      bone.quaternion.setFromUnitVectors(UP, dir.divideScalar(length));
      bone.scale.set(0.045, length, 0.045);
    }
  }

  root() { return this.points[0]; }
}
