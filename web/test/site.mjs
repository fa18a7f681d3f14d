// What the page's test and the docs' screenshot share: a static host for build-web/ (as any
// would serve the page: no special headers) and Debian's Chromium, headless, with WebGL 2 on
// SwiftShader.
import { chromium } from "playwright-core";
import { createServer } from "node:http";
import { readFile } from "node:fs/promises";
import { extname, join, normalize } from "node:path";

const types = { ".html": "text/html", ".js": "text/javascript", ".css": "text/css",
  ".wasm": "application/wasm", ".data": "application/octet-stream" };

// Serves the folder `site` on a free port of 127.0.0.1 (server.address().port).
export async function serve(site) {
  const server = createServer(async (request, response) => {
    let path = normalize(decodeURIComponent(new URL(request.url, "http://x").pathname));
    if (path === "/") path = "/index.html";
    try {
      const body = await readFile(join(site, path));
      response.writeHead(200, { "Content-Type": types[extname(path)] || "application/octet-stream" });
      response.end(body);
    } catch {
      response.writeHead(404);
      response.end();
    }
  });
  await new Promise((resolve) => server.listen(0, "127.0.0.1", resolve));
  return server;
}

export function launch(executable = "/usr/bin/chromium") {
  return chromium.launch({
    executablePath: executable,
    args: ["--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--use-gl=angle",
      "--disable-background-networking", "--disable-component-update", "--no-first-run"],
  });
}
