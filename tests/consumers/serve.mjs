// A loopback web server for one three.js rendering (module scripts do not load from file://):
// serves the page, three.js from node_modules and one glTF file, then waits for the page to POST
// its result, writes it to OUT and exits 0. The page's POST /error exits 1; no result within
// the time limit exits 2, so a page that never loads cannot hang a test.
//   node serve.mjs MODEL.glb OUT [SECONDS]    prints "port N" once it listens
import {createServer} from 'node:http';
import {readFile, writeFile} from 'node:fs/promises';
import {dirname, extname, join, normalize} from 'node:path';
import {fileURLToPath} from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const [model, out, seconds = '120'] = process.argv.slice(2);
if (!model || !out) {
  console.error('usage: node serve.mjs MODEL.glb OUT [SECONDS]');
  process.exit(64);
}
const types = {
  '.html': 'text/html',
  '.js': 'text/javascript',
  '.mjs': 'text/javascript',
  '.glb': 'model/gltf-binary',
  '.gltf': 'model/gltf+json',
  '.bin': 'application/octet-stream',
};
// URL prefix → directory on disk; nothing outside these is served.
const roots = [
  ['/three/', join(here, 'node_modules', 'three')],
  ['/page/', here],
  ['/model/', dirname(model)],
];

function resolve(url) {
  for (const [prefix, dir] of roots) {
    if (!url.startsWith(prefix)) continue;
    const file = normalize(join(dir, decodeURIComponent(url.slice(prefix.length))));
    if (file.startsWith(dir)) return file;
  }
  return null;
}

async function body(request) {
  const chunks = [];
  for await (const chunk of request) chunks.push(chunk);
  return Buffer.concat(chunks);
}

const server = createServer(async (request, response) => {
  const url = request.url.split('?')[0];
  if (request.method === 'POST') {
    const data = await body(request);
    response.end('ok');
    if (url === '/result') {
      await writeFile(out, data);
      process.exit(0);
    }
    console.error('page error: ' + data.toString());
    process.exit(1);
  }
  const file = resolve(url);
  try {
    if (file === null) throw new Error('outside the served roots');
    const data = await readFile(file);
    response.writeHead(200, {'Content-Type': types[extname(file)] ?? 'application/octet-stream'});
    response.end(data);
  } catch (error) {
    response.writeHead(404);
    response.end();
  }
});
server.listen(0, '127.0.0.1', () => console.log('port ' + server.address().port));
setTimeout(() => {
  console.error('no result from the page within ' + seconds + ' s');
  process.exit(2);
}, Number(seconds) * 1000);
