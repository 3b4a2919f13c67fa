// Usage: node compare_positions.mjs OURS.json THREE.json TOLERANCE_M
//
// Compares two world-position files of the shape
//   {"fps": F, "joints": [{"name", "parent"}], "positions": [frame][joint][x, y, z]}
// OURS.json from `motiongraph convert`, THREE.json from bvh_world_positions.mjs.
// Joints are matched by name. Every joint of ours must be found in THREE.json,
// end joints ("<joint>_end", which bvh_world_positions.mjs names the same way)
// included; a joint of ours that is not found, a parent that differs, an extra
// three.js joint that is not an end site, a different frame count or frame
// rate, or any position further apart than TOLERANCE_M metres (Euclidean
// distance) fails with exit status 1, printing the worst joint and frame. On
// success prints one summary line.

import { readFileSync } from 'node:fs';

function fail(message) {
	console.error(`compare_positions: FAIL: ${message}`);
	process.exit(1);
}

if (process.argv.length !== 5) {
	console.error('usage: node compare_positions.mjs OURS.json THREE.json TOLERANCE_M');
	process.exit(2);
}
const [oursPath, threePath, toleranceArg] = process.argv.slice(2);
const tolerance = Number(toleranceArg);
if (!(tolerance >= 0)) fail(`bad tolerance "${toleranceArg}"`);

function load(path) {
	let data;
	try {
		data = JSON.parse(readFileSync(path, 'utf8'));
	} catch (e) {
		fail(`cannot read ${path}: ${e.message}`);
	}
	if (typeof data.fps !== 'number' || !Array.isArray(data.joints) || !Array.isArray(data.positions)) {
		fail(`${path}: expected {fps, joints, positions}`);
	}
	const byName = new Map();
	data.joints.forEach((joint, i) => {
		if (byName.has(joint.name)) fail(`${path}: two joints named "${joint.name}"`);
		byName.set(joint.name, i);
	});
	data.positions.forEach((frame, f) => {
		if (!Array.isArray(frame) || frame.length !== data.joints.length) {
			fail(`${path}: frame ${f} has ${frame?.length} joints, expected ${data.joints.length}`);
		}
	});
	return { ...data, byName };
}

const ours = load(oursPath);
const three = load(threePath);

const frameCount = ours.positions.length;
if (three.positions.length !== frameCount) {
	fail(`frame count: ours ${frameCount}, three.js ${three.positions.length}`);
}
if (frameCount === 0) fail('no frames');
if (Math.abs(ours.fps - three.fps) > 1e-6 * ours.fps) fail(`fps: ours ${ours.fps}, three.js ${three.fps}`);

// Match joints by name; parents must match by name too.
const isEnd = (joint, joints) => !joints.some((other) => other.parent === joints.indexOf(joint));
const parentName = (data, joint) => (joint.parent < 0 ? null : data.joints[joint.parent].name);
const pairs = [];
const missing = [];
for (const [i, joint] of ours.joints.entries()) {
	const j = three.byName.get(joint.name);
	if (j === undefined) {
		missing.push(joint.name);
		continue;
	}
	const ourParent = parentName(ours, joint);
	const threeParent = parentName(three, three.joints[j]);
	if (ourParent !== threeParent) fail(`joint ${joint.name}: parent is ${ourParent} in ours, ${threeParent} in three.js`);
	pairs.push([i, j]);
}
const endCount = ours.joints.filter((joint) => joint.name.endsWith('_end') && isEnd(joint, ours.joints)).length;
if (missing.length > 0) {
	fail(`${missing.length} of our ${ours.joints.length} joints (${endCount} of them end joints) not found in three.js's skeleton: ${missing.join(', ')}`);
}
// Our writer gives a leaf joint that has no end joint of ours a zero-length
// "End Site"; three.js then has an end bone we do not. Such extra end sites are
// allowed (and counted in the summary); any other extra joint fails.
const extraEnds = [];
for (const joint of three.joints) {
	if (ours.byName.has(joint.name)) continue;
	if (!(joint.name.endsWith('_end') && isEnd(joint, three.joints))) fail(`three.js has a joint we do not: ${joint.name}`);
	extraEnds.push(joint.name);
}

let worst = { error: -1 };
for (let f = 0; f < frameCount; f++) {
	const a = ours.positions[f];
	const b = three.positions[f];
	for (const [i, j] of pairs) {
		const d = Math.hypot(a[i][0] - b[j][0], a[i][1] - b[j][1], a[i][2] - b[j][2]);
		if (Number.isNaN(d)) fail(`joint ${ours.joints[i].name} frame ${f}: not a number: ours [${a[i]}] three.js [${b[j]}]`);
		if (d > worst.error) worst = { error: d, frame: f, name: ours.joints[i].name, ours: a[i], three: b[j] };
	}
}

const mm = (metres) => (metres * 1000).toPrecision(3);
const where = `joint ${worst.name} frame ${worst.frame}: ours [${worst.ours}] three.js [${worst.three}]`;
if (!(worst.error <= tolerance)) {
	fail(`max error ${mm(worst.error)} mm > tolerance ${mm(tolerance)} mm at ${where}`);
}
const extraNote = extraEnds.length > 0 ? `; ${extraEnds.length} extra three.js end sites not compared: ${extraEnds.join(', ')}` : '';
console.log(`OK ${pairs.length} joints (${endCount} end sites) x ${frameCount} frames, max error ${mm(worst.error)} mm (tolerance ${mm(tolerance)} mm) at ${worst.name} frame ${worst.frame}${extraNote}`);
