// A shaded figure from joint positions: a capsule-like cylinder per bone and a sphere per joint,
// casting shadows. Positions come flat per frame: [x0, y0, z0, x1, ...] in metres, y up.
import * as THREE from 'three';

const UP = new THREE.Vector3(0, 1, 0);

export class Figure {
  constructor(joints, color = 0xe07b39) {
    this.joints = joints;
    this.group = new THREE.Group();
    this.offset = new THREE.Vector3();
    const material = new THREE.MeshStandardMaterial({ color, roughness: 0.55, metalness: 0.05 });
    const jointMaterial = new THREE.MeshStandardMaterial({ color: 0x3a4a5c, roughness: 0.6 });
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
