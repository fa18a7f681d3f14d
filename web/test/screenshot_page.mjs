// A screenshot of the whole page (the picture and its panel) at URL, once it has drawn 10
// frames, for the docs (scripts/make-doc-images.sh).
//   node web/test/screenshot_page.mjs URL OUT.png
import { launch } from "./site.mjs";

const [url, out] = process.argv.slice(2);
if (!url || !out) {
  console.error("usage: node screenshot_page.mjs URL OUT.png");
  process.exit(2);
}
const browser = await launch();
try {
  const page = await browser.newPage({ viewport: { width: 660, height: 560 } });
  await page.goto(url);
  await page.waitForFunction(() => Number(document.body.dataset.frames || 0) >= 10, null,
    { timeout: 120000 });
  await page.screenshot({ path: out, fullPage: true });
} finally {
  await browser.close();
}
