// spz-js (npm) as an oracle: PLY -> .spz (its own writer) or .spz -> PLY.
//   node spzjs_convert.mjs IN OUT
import { readFileSync, writeFileSync, createReadStream } from 'fs';
import { Readable } from 'stream';
import { loadPly, loadSpz, serializePly, serializeSpz } from 'spz-js';

const [input, output] = process.argv.slice(2);
const gs = input.endsWith('.spz') ? await loadSpz(readFileSync(input))
  : await loadPly(Readable.toWeb(createReadStream(input)));
const bytes = output.endsWith('.spz') ? await serializeSpz(gs) : serializePly(gs);
writeFileSync(output, Buffer.from(bytes));
