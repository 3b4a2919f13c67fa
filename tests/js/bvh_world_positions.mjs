// Usage: node bvh_world_positions.mjs FILE.bvh OUT.json
//
// Reads FILE.bvh with three.js's BVHLoader, plays every frame of the loaded clip
// on the loaded skeleton with an AnimationMixer (as a three.js viewer would), and
// writes the world position of every bone as
//   {"fps": F, "joints": [{"name", "parent"}], "positions": [frame][joint][x, y, z]}
// which is the shape `motiongraph convert X -o Y.json` writes, so that
// compare_positions.mjs can check the two against each other. No unit
// conversion is done: BVHLoader uses the file's units (ours are metres).
//
// What BVHLoader (three 0.187.0, examples/jsm/loaders/BVHLoader.js) does, read
// from its source:
// - Bones: one THREE.Bone per ROOT/JOINT, named with the BVH name, plus one Bone
//   per "End Site", which BVHLoader names literally "ENDSITE" (every end site
//   gets that same name; they have no animation track). skeleton.bones lists them
//   depth-first in file order, end sites included. We rename each end site to
//   "<parent name>_end" (the name our JSON gives end joints, e.g. "ltoes_end"),
//   adding a number if a joint had more than one end site.
// - OFFSET: becomes bone.position at rest. The clip then gives EVERY non-end bone
//   a ".position" track whose value is OFFSET + the frame's position-channel
//   values (zero for joints without position channels). So position channels are
//   ADDED to the OFFSET (a translation relative to the OFFSET), not used as an
//   absolute local position replacing it. Our writer puts "OFFSET 0 0 0" on the
//   root, so both readings agree for our files.
// - Rotations: for each rotation channel in the order listed in CHANNELS, the
//   quaternion is post-multiplied by the rotation about that axis
//   (q = q * axisAngle(axis, deg)), i.e. R = R(first) * R(second) * R(third):
//   intrinsic rotations in the listed order, per joint, so per-joint orders such
//   as "Zrotation Xrotation Yrotation" are honoured. Channels may be interleaved
//   in any order; position and rotation channels are independent of each other.
// - The clip has one ".position" (VectorKeyframeTrack) and one ".quaternion"
//   (QuaternionKeyframeTrack) track per non-end bone, with key times i * frameTime.
//   KeyframeTrack stores times and values as Float32Array, so three.js itself
//   rounds every position and quaternion to single precision (~1e-7 relative).
// - "Frames:" is the 2nd token of its line and "Frame Time:" the 3rd; the clip
//   duration is the last key time.
//
// Playback here: an AnimationMixer on the root bone, one action set to LoopOnce
// with clampWhenFinished (the default LoopRepeat would wrap the last frame, time
// == duration, back to frame 0), and mixer.setTime(t) with t the key time of the
// frame as three.js stores it (float32 of frame * frameTime, so the interpolation
// weight is exactly 0 and no neighbouring frame leaks in). After each setTime we
// check that every bone holds its track's key value for that frame: a track
// whose name PropertyBinding could not bind (a BVH joint name containing one of
// . : / [ ], or two joints with the same name) would otherwise just be skipped.

import { readFileSync, writeFileSync } from 'node:fs';
import { AnimationMixer, LoopOnce, Vector3 } from 'three';
import { BVHLoader } from 'three/addons/loaders/BVHLoader.js';

function fail(message) {
	console.error(`bvh_world_positions: ${message}`);
	process.exit(1);
}

if (process.argv.length !== 4) {
	console.error('usage: node bvh_world_positions.mjs FILE.bvh OUT.json');
	process.exit(2);
}
const [inPath, outPath] = process.argv.slice(2);

let text;
try {
	text = readFileSync(inPath, 'utf8');
} catch (e) {
	fail(`cannot read ${inPath}: ${e.message}`);
}

// BVHLoader reports malformed input with console.error and carries on; treat
// any such message as a failure of this test.
const loaderErrors = [];
const consoleError = console.error;
const consoleWarn = console.warn;
console.error = (...args) => loaderErrors.push(args.join(' '));
console.warn = (...args) => loaderErrors.push(args.join(' '));
let result;
try {
	result = new BVHLoader().parse(text);
} catch (e) {
	loaderErrors.push(`exception: ${e.stack ?? e}`);
} finally {
	console.error = consoleError;
	console.warn = consoleWarn;
}
if (loaderErrors.length > 0) fail(`BVHLoader on ${inPath}:\n  ${loaderErrors.join('\n  ')}`);

const { skeleton, clip } = result;
const bones = skeleton.bones;
const root = bones[0];
if (root.parent !== null) fail('root bone has a parent');

// Frame count and frame time, as BVHLoader reads them (the clip's key times).
const tracks = clip.tracks;
if (tracks.length === 0) fail(`${inPath}: clip has no tracks`);
const times = tracks[0].times;
const frameCount = times.length;
for (const track of tracks) {
	if (track.times.length !== frameCount) fail(`track ${track.name} has ${track.times.length} keys, expected ${frameCount}`);
}
const motionHeader = /Frames:\s*(\d+)\s*[\r\n]+\s*Frame\s+Time:\s*(\S+)/i.exec(text);
if (!motionHeader) fail(`${inPath}: no "Frames:" / "Frame Time:" header`);
if (Number(motionHeader[1]) !== frameCount) fail(`header says ${motionHeader[1]} frames, clip has ${frameCount}`);
const frameTime = parseFloat(motionHeader[2]);
if (!(frameTime > 0)) fail(`bad frame time ${motionHeader[2]}`);

// Joint names and parents, end sites renamed to "<parent>_end".
const index = new Map(bones.map((bone, i) => [bone, i]));
const names = [];
const endCount = new Map();
for (const bone of bones) {
	if (bone.name === 'ENDSITE' && bone.children.length === 0 && bone.parent !== null) {
		const base = `${bone.parent.name}_end`;
		const n = (endCount.get(base) ?? 0) + 1;
		endCount.set(base, n);
		names.push(n === 1 ? base : `${base}${n}`);
	} else {
		names.push(bone.name);
	}
}
const joints = bones.map((bone, i) => ({
	name: names[i],
	parent: bone.parent === null ? -1 : index.get(bone.parent),
}));

// Which bone each track should drive, to check the mixer really drove it.
const bonesByName = new Map();
for (const bone of bones) {
	if (bone.name === 'ENDSITE') continue;
	if (bonesByName.has(bone.name)) fail(`two joints are named "${bone.name}"; three.js binds tracks by name`);
	bonesByName.set(bone.name, bone);
}
const checks = tracks.map((track) => {
	const dot = track.name.lastIndexOf('.');
	const boneName = track.name.slice(0, dot);
	const property = track.name.slice(dot + 1);
	const bone = bonesByName.get(boneName);
	if (!bone || (property !== 'position' && property !== 'quaternion')) fail(`unexpected track ${track.name}`);
	return { track, target: bone[property], size: property === 'position' ? 3 : 4 };
});

const mixer = new AnimationMixer(root);
const action = mixer.clipAction(clip);
action.setLoop(LoopOnce, 1);
action.clampWhenFinished = true;
action.play();

const world = new Vector3();
const positions = [];
for (let f = 0; f < frameCount; f++) {
	if (Math.abs(times[f] - f * frameTime) > 1e-6 * Math.max(1, f * frameTime)) {
		fail(`key time of frame ${f} is ${times[f]}, expected ${f * frameTime}`);
	}
	mixer.setTime(times[f]);
	for (const { track, target, size } of checks) {
		const expected = track.values.subarray(f * size, f * size + size);
		const actual = target.toArray();
		// quaternions q and -q are the same rotation
		const sign = size === 4 && actual[0] * expected[0] + actual[1] * expected[1] + actual[2] * expected[2] + actual[3] * expected[3] < 0 ? -1 : 1;
		for (let k = 0; k < size; k++) {
			if (Math.abs(sign * actual[k] - expected[k]) > 1e-6) {
				fail(`frame ${f}: mixer left ${track.name} at [${actual}], key value is [${Array.from(expected)}] (track not bound?)`);
			}
		}
	}
	root.updateMatrixWorld(true);
	positions.push(bones.map((bone) => world.setFromMatrixPosition(bone.matrixWorld).toArray()));
}

writeFileSync(outPath, JSON.stringify({ fps: 1 / frameTime, joints, positions }));
