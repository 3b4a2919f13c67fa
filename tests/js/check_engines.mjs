// Every npm package the project installs (the studio's web/ and the tests' tests/js lockfiles)
// must run on the Node.js that Debian 12 ships, not only on the Node.js of this machine: a
// newer Node.js here once hid a playwright-core that refused Debian's 18.x on a fresh machine.
// Checks each locked package's "engines.node" range against Debian 12's Node.js version and
// against the running one, and that the lockfiles pin what the package.json files ask for.
// Usage: node check_engines.mjs PROJECT_DIR
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import semver from 'semver';

// Debian 12 (bookworm) ships nodejs 18.20.4 (bookworm and bookworm-security, 2026); the
// oldest 18.x a bookworm point release may still carry is 18.19.0. Both must be admitted.
const DEBIAN12_NODE_VERSIONS = ['18.19.0', '18.20.4'];

const projectDir = process.argv[2];
if (!projectDir) {
  console.error('usage: node check_engines.mjs PROJECT_DIR');
  process.exit(2);
}

let failures = 0;
let checked = 0;
function fail(message) {
  console.log(`FAIL ${message}`);
  failures += 1;
}

for (const dir of ['web', 'tests/js']) {
  const lockPath = join(projectDir, dir, 'package-lock.json');
  const manifest = JSON.parse(readFileSync(join(projectDir, dir, 'package.json'), 'utf8'));
  const lock = JSON.parse(readFileSync(lockPath, 'utf8'));
  const packages = lock.packages || {};
  // The versions asked for are exact pins, and the lockfile holds exactly them.
  const wanted = { ...(manifest.dependencies || {}), ...(manifest.devDependencies || {}) };
  for (const [name, range] of Object.entries(wanted)) {
    if (!semver.valid(range)) fail(`${dir}/package.json: ${name} is '${range}', not an exact version`);
    const locked = packages[`node_modules/${name}`];
    if (!locked) fail(`${dir}/package-lock.json: ${name} is not locked`);
    else if (locked.version !== range) fail(`${dir}/package-lock.json: ${name} is ${locked.version}, package.json asks ${range}`);
  }
  for (const [path, info] of Object.entries(packages)) {
    if (path === '') continue;
    checked += 1;
    const name = path.replace(/^.*node_modules\//, '');
    const range = info.engines && info.engines.node;
    if (!range) continue;
    for (const version of [...DEBIAN12_NODE_VERSIONS, process.versions.node]) {
      if (!semver.satisfies(version, range)) {
        fail(`${dir}: ${name} ${info.version} needs Node.js ${range}, which excludes ${version}`
          + `${version === process.versions.node ? ' (this machine)' : ' (Debian 12)'}`);
      }
    }
  }
}
// playwright-core also refuses to start below a Node.js major of its own (lib/bootstrap.js),
// which is what a fresh Debian 12 met: read it from the installed package.
try {
  const bootstrap = readFileSync(join(projectDir, 'tests/js/node_modules/playwright-core/lib/bootstrap.js'), 'utf8');
  const m = bootstrap.match(/minimumMajorNodeVersion\s*=\s*(\d+)/);
  if (!m) fail('playwright-core/lib/bootstrap.js: no minimumMajorNodeVersion found (the check needs updating)');
  else if (semver.major(DEBIAN12_NODE_VERSIONS[0]) < Number(m[1])) {
    fail(`playwright-core refuses Node.js below ${m[1]} at start-up; Debian 12 has ${DEBIAN12_NODE_VERSIONS[0]}`);
  }
} catch (e) {
  fail(`playwright-core is not installed in tests/js (run npm ci there): ${e.message}`);
}
// The check itself must be able to fail: a range Debian's Node.js is known not to meet.
if (semver.satisfies(DEBIAN12_NODE_VERSIONS[1], '>=20')) fail('semver admits 18.20.4 in >=20');

console.log(`${checked} locked packages checked against Node.js ${DEBIAN12_NODE_VERSIONS.join(', ')} `
  + `(Debian 12) and ${process.versions.node} (this machine)`);
if (failures > 0) {
  console.log(`check_engines: ${failures} failure(s)`);
  process.exit(1);
}
