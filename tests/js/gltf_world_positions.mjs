// Usage: node gltf_world_positions.mjs FILE.glb|FILE.gltf OUT.json [ANIMATION]
//
// Without ANIMATION the file must hold one animation, named as the file; with it, that one of
// the file's animations is played (an animation set: every animation must key the same
// tracks, so that each poses the whole figure whichever played before it).
//
// Reads FILE.glb (or a .gltf, its buffer embedded) as a viewer or an engine would: first the Khronos glTF validator
// (npm "gltf-validator", the reference implementation of the spec's rules), which
// must report no error, warning, info or hint; then three.js's GLTFLoader, whose
// animation is played on the loaded scene with an AnimationMixer, every frame in
// turn. Writes the world position of every joint (the skin's joints, in skin
// order, named as in the file) as
//   {"fps": F, "joints": [{"name", "parent"}], "positions": [frame][joint][x, y, z]}
// the shape `motiongraph convert X -o Y.json` writes, for compare_positions.mjs.
//
// It also checks the skin as three.js draws it: the file's stick figure has one
// octahedral bone per joint and child, 24 vertices, its vertex 0 the bone's head
// and vertex 3 its tip, all bound to the parent joint alone. Skinned on the GPU's
// formula (SkinnedMesh.applyBoneTransform: bind matrix, bone matrix times inverse
// bind matrix, weights), the head must sit on its joint in every frame, and the tip
// on the child joint it was made to (the one at the tip at rest) whenever that
// child's translation is not animated: the tip lies off the joint the bone hangs
// from, so it lands right only when the inverse bind matrix undoes the rest
// rotation and translation both.
//
// Key times: the glTF input accessor holds frame / fps in float32; three.js keeps
// them in a Float32Array, so mixer.setTime(times[f]) lands exactly on key f.
// The frame rate is not stored in glTF; it is taken from the first two key times
// (as float32: compare_positions.mjs allows 1e-6 relative).

import { readFileSync, writeFileSync } from 'node:fs';
import validator from 'gltf-validator';
import { AnimationMixer, LoopOnce, Vector3 } from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

// Node has no ProgressEvent, which three's FileLoader sends as it reads a .gltf's buffer from its
// data URI (a browser has one): the loader needs only its fields.
globalThis.ProgressEvent ??= class ProgressEvent extends Event {
	constructor(type, init = {}) {
		super(type);
		Object.assign(this, init);
	}
};

function fail(message) {
	console.error(`gltf_world_positions: ${message}`);
	process.exit(1);
}

if (process.argv.length !== 4 && process.argv.length !== 5) {
	console.error('usage: node gltf_world_positions.mjs FILE.glb OUT.json [ANIMATION]');
	process.exit(2);
}
const [inPath, outPath, animationName] = process.argv.slice(2);

let bytes;
try {
	bytes = readFileSync(inPath);
} catch (e) {
	fail(`cannot read ${inPath}: ${e.message}`);
}

const report = await validator.validateBytes(new Uint8Array(bytes), { maxIssues: 20 });
const issues = report.issues;
if (issues.numErrors + issues.numWarnings + issues.numInfos + issues.numHints > 0) {
	fail(`the glTF validator on ${inPath}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ` +
		`${issues.numInfos} infos, ${issues.numHints} hints:\n  ${issues.messages.map((m) => `${m.code} at ${m.pointer}: ${m.message}`).join('\n  ')}`);
}

const arrayBuffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
const gltf = await new Promise((resolve, reject) => new GLTFLoader().parse(arrayBuffer, '', resolve, reject))
	.catch((e) => fail(`GLTFLoader on ${inPath}: ${e.stack ?? e}`));

const json = gltf.parser.json;
if (!json.skins || json.skins.length !== 1) fail(`expected one skin, found ${json.skins?.length ?? 0}`);
let clip;
if (animationName === undefined) {
	if (gltf.animations.length !== 1) fail(`expected one animation, found ${gltf.animations.length}`);
	// Named as the file, without its extension.
	const stem = inPath.replace(/^.*\//, '').replace(/\.(glb|gltf)$/, '');
	if (json.animations[0].name !== stem) fail(`the animation is named '${json.animations[0].name}', not '${stem}'`);
	clip = gltf.animations[0];
} else {
	clip = gltf.animations.find((a) => a.name === animationName);
	if (!clip) fail(`no animation '${animationName}' among ${gltf.animations.map((a) => a.name).join(', ')}`);
	const keyed = (a) => a.tracks.map((t) => t.name).sort().join(' ');
	for (const other of gltf.animations) {
		if (keyed(other) !== keyed(clip)) fail(`animations '${other.name}' and '${clip.name}' key different tracks`);
	}
}
const skinJoints = json.skins[0].joints;
const nodes = await gltf.parser.getDependencies('node');
const bones = skinJoints.map((n) => nodes[n]);
for (const [i, bone] of bones.entries()) {
	if (!bone.isBone) fail(`skin joint ${i} (${json.nodes[skinJoints[i]].name}) did not load as a Bone`);
}

// Joint names as the file has them, parents as skin-joint indices.
const jointOf = new Map(skinJoints.map((n, i) => [n, i]));
const parentNode = new Map();
json.nodes.forEach((node, n) => (node.children ?? []).forEach((child) => parentNode.set(child, n)));
const joints = skinJoints.map((n) => ({
	name: json.nodes[n].name,
	parent: parentNode.has(n) ? (jointOf.get(parentNode.get(n)) ?? -1) : -1,
}));

const times = clip.tracks[0].times;
const frameCount = times.length;
for (const track of clip.tracks) {
	if (track.times.length !== frameCount) fail(`track ${track.name} has ${track.times.length} keys, expected ${frameCount}`);
}
const fps = frameCount > 1 ? 1 / (times[1] - times[0]) : 0;

let mesh = null;
gltf.scene.traverse((object) => {
	if (object.isSkinnedMesh) mesh = object;
});
// [vertex, joint]: each bone's head on the joint it hangs from, its tip on the child it points to.
const onJoints = [];
const world = new Vector3();
const vertex = new Vector3();
if (!mesh) fail('no skinned mesh (the stick figure) in the scene');
{
	const position = mesh.geometry.getAttribute('position');
	const skinIndex = mesh.geometry.getAttribute('skinIndex');
	if (position.count % 24 !== 0) fail(`the stick figure has ${position.count} vertices, not 24 per bone`);
	// At rest (no animation played yet) the mesh is in its bind pose, where the joints are.
	gltf.scene.updateMatrixWorld(true);
	const animatedTranslation = new Set(clip.tracks.filter((t) => t.name.endsWith('.position'))
		.map((t) => t.name.slice(0, t.name.lastIndexOf('.'))));
	for (let v = 0; v < position.count; v += 24) {
		onJoints.push([v, skinIndex.getX(v)]);
		vertex.fromBufferAttribute(position, v + 3).applyMatrix4(mesh.matrixWorld);
		const child = bones.findIndex((bone) => world.setFromMatrixPosition(bone.matrixWorld).distanceTo(vertex) < 1e-5);
		if (child < 0) fail(`the tip of bone ${v / 24} is on no joint at rest`);
		if (!animatedTranslation.has(bones[child].name)) onJoints.push([v + 3, child]);
	}
}

const mixer = new AnimationMixer(gltf.scene);
const action = mixer.clipAction(clip);
action.setLoop(LoopOnce, 1);
action.clampWhenFinished = true;
action.play();

const positions = [];
let worstSkin = 0;
for (let f = 0; f < frameCount; f++) {
	mixer.setTime(times[f]);
	gltf.scene.updateMatrixWorld(true);
	const frame = bones.map((bone) => world.setFromMatrixPosition(bone.matrixWorld).toArray());
	positions.push(frame);
	mesh.skeleton.update();
	for (const [v, joint] of onJoints) {
		vertex.fromBufferAttribute(mesh.geometry.getAttribute('position'), v);
		mesh.applyBoneTransform(v, vertex);
		vertex.applyMatrix4(mesh.matrixWorld);
		const [x, y, z] = frame[joint];
		worstSkin = Math.max(worstSkin, Math.hypot(vertex.x - x, vertex.y - y, vertex.z - z));
	}
}
if (worstSkin > 1e-5) fail(`a bone's head or tip, skinned, lies ${worstSkin} m from its joint`);

writeFileSync(outPath, JSON.stringify({ fps, joints, positions }));
console.log(`gltf_world_positions: ${inPath}: ${joints.length} joints, ${frameCount} frames, ` +
	`${onJoints.length} bone heads and tips skinned onto their joints within ${worstSkin.toExponential(1)} m`);
