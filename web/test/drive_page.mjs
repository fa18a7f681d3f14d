// Drives the web page (build-web/) in Debian's Chromium, headless on SwiftShader, as a user
// would, and writes what it saw into OUT for tests/test_web_page.cpp to judge:
//   terrell.png, street.png, street-lit.png, black-hole.png, stars.png   each scene at 640x360
//                              (exposure 0, paused at the scene's time; street-lit's lamps and
//                              shadows by the lighting pass; the last two's stars from the
//                              catalogue in the page's data)
//   (results.json's opened)    for every bundled scene opened from its link: the scene the link
//                              shows then and the page's message
//   (results.json's unopened_message)  what the page says of a link to a scene it cannot open
//   terrell-auto.png           terrell at 640x360 at its own, automatic exposure, paused (and
//                              results.json's terrell_auto_ev, the EV the page applied)
//   key-before.png, key-after.png   street before and after the W key
//   reset.png                  street after W, a turn and R (back at the scene's camera)
//   (results.json's infall_clock)  the clock near a hole: the page's time scale, and the proper
//                              time shown after some frames against the wall time flown
//   (results.json's probes)    terrell's probes: two from a link (probe=x,y;x,y), their readouts
//                              and marks, then a click's, then none after X
//   dragged.png                street after a drag on the picture
//   preset.png, by-hand.png    a preset link, and the same switches set in the panel
//   drop-before.png, drop-after.png  street before and after a scene with an error is dropped
//   (results.json's refusals)  what the page says of each scene tests/data/refused-requests.json
//                              refuses as a scene, dropped on it
//   texture-mapping.png        a user's scene and its image, chosen in the file dialog
//   lit-texture-mapping.png    the same lit by a lamp under the spectral model (the scene
//                              beside it, lit-texture-mapping.json, with uv-grid.png)
//   hole-shadows.png           bodies near a black hole shadowing each other
//                              (tests/data/hole-shadows.json)
//   screenshot-button.png      what the screenshot button downloads (and the canvas then)
//   results.json               the numbers: speeds, messages, load times, frame rate, console
//
//   node web/test/drive_page.mjs SITE OUT [CHROMIUM]
import { writeFile, mkdir, readFile, copyFile } from "node:fs/promises";
import { join } from "node:path";
import { serve, launch } from "./site.mjs";

const [site, out, executable] = process.argv.slice(2);
if (!site || !out) {
  console.error("usage: node drive_page.mjs SITE OUT [CHROMIUM]");
  process.exit(2);
}
await mkdir(out, { recursive: true });
const server = await serve(site);
const base = `http://127.0.0.1:${server.address().port}/`;
const browser = await launch(executable);
const results = { console: [], load_ms: {} };
const step = (text) => console.error(`drive_page: ${text}`);

// A fresh page at `hash`, once it has drawn `frames` frames.
async function open(hash, frames = 3, options = {}) {
  const page = await browser.newPage({ viewport: { width: 1100, height: 800 }, ...options });
  page.on("console", (m) => { if (m.type() === "error") results.console.push(m.text()); });
  page.on("pageerror", (e) => results.console.push(String(e)));
  await page.goto(base + "#" + hash);
  await framesAfter(page, 0, frames);
  return page;
}
const count = (page, key) => page.evaluate((k) => Number(document.body.dataset[k] || 0), key);
async function framesAfter(page, from, frames = 3) {
  await page.waitForFunction((n) => Number(document.body.dataset.frames || 0) >= n,
    from + frames, { timeout: 120000 });
}
async function settle(page, frames = 3) { await framesAfter(page, await count(page, "frames"), frames); }
async function shot(page, name) {
  const url = await page.evaluate(() => document.getElementById("canvas").toDataURL("image/png"));
  await writeFile(join(out, name), Buffer.from(url.split(",")[1], "base64"));
}
const text = (page, id) => page.evaluate((i) => document.getElementById(i).textContent, id);
const still = "exposure=0&paused=on";

try {
  for (const scene of ["terrell", "street", "street-lit", "black-hole", "stars"]) {
    step(`${scene} at 640x360`);
    const page = await open(`scene=${scene}&${still}`);
    results.load_ms[scene] = await page.evaluate(() => Number(document.body.dataset.firstFrame));
    await shot(page, `${scene}.png`);
    await page.close();
  }

  step("every bundled scene from its link");
  {
    const page = await open(`scene=street&${still}`, 1);
    const names = await page.evaluate(() =>
      [...document.getElementById("scene").options].map((o) => o.value));
    await page.close();
    results.opened = {};
    for (const name of names) {
      const opened = await open(`scene=${name}&paused=on`, 1);
      results.opened[name] = {
        scene: await opened.evaluate(() => new URLSearchParams(location.hash.slice(1)).get("scene")),
        message: await text(opened, "message"),
      };
      await opened.close();
    }
  }

  step("a link to a scene the page cannot open");
  {
    // The hole has no classical picture: the program refuses it, and so does the page.
    const page = await open(`scene=black-hole&relativity=off&${still}`);
    results.unopened_message = await text(page, "message");
    results.unopened_shows = await page.evaluate(() =>
      new URLSearchParams(location.hash.slice(1)).get("scene"));
    await page.close();
  }

  step("terrell at its automatic exposure");
  {
    const page = await open("scene=terrell&paused=on");
    results.terrell_auto_ev = Number(await page.evaluate(() => document.getElementById("numbers").dataset.exposure));
    await shot(page, "terrell-auto.png");
    await page.close();
  }

  step("the screenshot button");
  {
    const page = await open(`scene=terrell&${still}`);
    const [download] = await Promise.all([page.waitForEvent("download"),
      page.click("#screenshot")]);
    results.screenshot_name = download.suggestedFilename();
    await download.saveAs(join(out, "screenshot-button.png"));
    await shot(page, "screenshot-canvas.png");
    await page.close();
  }

  step("the W key");
  {
    const page = await open(`scene=street&${still}`);
    results.beta_before_key = Number(await page.evaluate(() => document.getElementById("numbers").dataset.beta));
    await shot(page, "key-before.png");
    await page.keyboard.press("w");
    await settle(page);
    results.beta_after_key = Number(await page.evaluate(() => document.getElementById("numbers").dataset.beta));
    await shot(page, "key-after.png");
    await page.close();
  }

  step("R after a flight");
  {
    const page = await open(`scene=street&${still}`);
    await page.keyboard.press("w");
    await page.keyboard.down("ArrowLeft");
    await settle(page);
    await page.keyboard.up("ArrowLeft");
    results.beta_before_reset = Number(await page.evaluate(() => document.getElementById("numbers").dataset.beta));
    const loads = await count(page, "loads");
    await page.keyboard.press("r");
    await page.waitForFunction((n) => Number(document.body.dataset.loads) > n, loads);
    await settle(page);
    results.beta_after_reset = Number(await page.evaluate(() => document.getElementById("numbers").dataset.beta));
    results.hash_after_reset = await page.evaluate(() => location.hash);
    await shot(page, "reset.png");
    await page.close();
  }

  step("the clock near a hole");
  {
    const page = await open("scene=infall&exposure=0", 2);
    const start = await page.evaluate(() => [Number(document.getElementById("numbers").dataset.properTime), performance.now()]);
    await page.waitForTimeout(2000);
    await settle(page, 2);
    const end = await page.evaluate(() => [Number(document.getElementById("numbers").dataset.properTime), performance.now()]);
    results.infall_clock = {
      time_scale: await page.evaluate(() => Number(document.body.dataset.timeScale)),
      proper_time: end[0] - start[0],
      wall_seconds: (end[1] - start[1]) / 1000,
    };
    await page.close();
  }

  step("probes: a link's two and their ruler, a click, X");
  {
    const probes = (page) => page.evaluate(() => ({
      probes: JSON.parse(document.body.dataset.probes || "[]"),
      text: document.getElementById("probes").textContent,
      marks: document.querySelectorAll(".probe-mark").length,
      probe: new URLSearchParams(location.hash.slice(1)).get("probe"),
    }));
    const page = await open(`scene=terrell&${still}&probe=466.5,171.5;289.5,180.5`);
    const from_link = await probes(page);
    // A click on canvas pixel (100, 20), the sky: a third probe starts again.
    const box = await page.evaluate(() => {
      const b = document.getElementById("canvas").getBoundingClientRect();
      return { x: b.left, y: b.top, w: b.width, h: b.height };
    });
    await page.mouse.click(box.x + (100.5 * box.w) / 640, box.y + (20.5 * box.h) / 360);
    await settle(page);
    const clicked = await probes(page);
    await page.keyboard.press("x");
    await settle(page);
    results.probes = { from_link, clicked, cleared: await probes(page) };
    await page.close();
  }

  step("a drag on the picture, and the touch screen's joystick");
  {
    const page = await open(`scene=street&${still}`);
    await page.mouse.move(400, 200);
    await page.mouse.down();
    await page.mouse.move(300, 200, { steps: 5 });
    await page.mouse.up();
    await settle(page);
    await shot(page, "dragged.png");
    results.yaw_after_drag = await page.evaluate(() => Number(new URLSearchParams(location.hash.slice(1)).get("yaw")));
    await page.close();
  }
  {
    // A finger holding the joystick up for a second: faster (touch events, as a tablet sends).
    const page = await open(`scene=street&${still}`, 3, { hasTouch: true, isMobile: true });
    const before = Number(await page.evaluate(() => document.getElementById("numbers").dataset.beta));
    const box = await page.evaluate(() => {
      const b = document.getElementById("joystick").getBoundingClientRect();
      return { hidden: document.getElementById("joystick").hidden, x: b.left + b.width / 2, y: b.top };
    });
    results.joystick_shown = !box.hidden;
    const touch = await page.context().newCDPSession(page);
    const at = (y) => [{ x: box.x, y }];
    await touch.send("Input.dispatchTouchEvent", { type: "touchStart", touchPoints: at(box.y + 60) });
    await touch.send("Input.dispatchTouchEvent", { type: "touchMove", touchPoints: at(box.y + 30) });
    await touch.send("Input.dispatchTouchEvent", { type: "touchMove", touchPoints: at(box.y + 2) });
    await page.waitForTimeout(1000);
    await touch.send("Input.dispatchTouchEvent", { type: "touchEnd", touchPoints: [] });
    await settle(page);
    results.joystick_beta = [before,
      Number(await page.evaluate(() => document.getElementById("numbers").dataset.beta))];
    await page.close();
  }

  step("a preset link, and its switches set by hand");
  {
    const preset = await open(`scene=street&beta=0.9&doppler=off&${still}`);
    await shot(preset, "preset.png");
    await preset.close();
    const page = await open(`scene=street&${still}`);
    const loads = await count(page, "loads");
    await page.selectOption("#doppler", "off");
    await page.waitForFunction((n) => Number(document.body.dataset.loads) > n, loads);
    await page.evaluate(() => {
      const slider = document.getElementById("beta");
      slider.value = "0.9";
      slider.dispatchEvent(new Event("input"));
    });
    await settle(page);
    await shot(page, "by-hand.png");
    results.hash_by_hand = await page.evaluate(() => location.hash);
    await page.close();
  }

  step("a dropped scene with an error");
  {
    const page = await open(`scene=street&${still}`);
    await shot(page, "drop-before.png");
    const loads = await count(page, "loads");
    await page.evaluate(() => {
      const files = new DataTransfer();
      files.items.add(new File(['{\n  "camera": {"fov": 60},\n  "objectz": []\n}\n'], "bad.json"));
      window.dispatchEvent(new DragEvent("drop", { dataTransfer: files, cancelable: true }));
    });
    await page.waitForFunction((n) => Number(document.body.dataset.loads) > n, loads);
    results.drop_message = await text(page, "message");
    await settle(page);
    await shot(page, "drop-after.png");
    await page.close();
  }

  step("scenes the library's rules refuse, dropped");
  {
    // Each scene of tests/data/refused-requests.json that is refused as a scene (not for an
    // output variable or a locate, which the page does not ask for): the page shows the message
    // the program prints.
    const cases = JSON.parse(await readFile(join(site, "..", "tests/data/refused-requests.json"),
      "utf8")).cases.filter((c) => !c.render && !c.locate);
    const page = await open(`scene=street&${still}`);
    results.refusals = {};
    for (const c of cases) {
      const loads = await count(page, "loads");
      await page.evaluate(([name, text]) => {
        const files = new DataTransfer();
        files.items.add(new File([text], `${name}.json`));
        window.dispatchEvent(new DragEvent("drop", { dataTransfer: files, cancelable: true }));
      }, [c.name, JSON.stringify(c.scene, null, 1)]);
      await page.waitForFunction((n) => Number(document.body.dataset.loads) > n, loads);
      results.refusals[c.name] = await text(page, "message");
    }
    await page.close();
  }

  step("a user's scene and its image, from the file dialog");
  {
    const page = await open(`scene=street&${still}`);
    const loads = await count(page, "loads");
    await page.setInputFiles("#files", ["scenes/texture-mapping.json", "scenes/uv-grid.png"]
      .map((f) => join(site, "..", f)));
    await page.waitForFunction((n) => Number(document.body.dataset.loads) > n, loads, { timeout: 60000 });
    results.user_message = await text(page, "message");
    await settle(page);
    await shot(page, "texture-mapping.png");
    await page.close();
  }

  step("a lit texture under the spectral model, from the file dialog");
  {
    // texture-mapping.json with its materials lit by a lamp, the camera flying at 0.5c: the page
    // fits the coefficient table's columns the texture needs before it draws it.
    const json = await readFile(join(site, "..", "scenes/texture-mapping.json"), "utf8");
    const scene = JSON.parse(json.split("\n").filter((l) => !l.startsWith("//")).join("\n"));
    for (const o of scene.objects) o.material.unlit = false;
    scene.camera.velocity = [-0.25, -0.14, -0.28];
    scene.lights = [{ name: "lamp", type: "point", position: [3, 5, 4], intensity: 60 }];
    scene.render = { doppler: "spectral" };
    await writeFile(join(out, "lit-texture-mapping.json"), JSON.stringify(scene, null, 1));
    await copyFile(join(site, "..", "scenes/uv-grid.png"), join(out, "uv-grid.png"));
    const page = await open(`scene=street&${still}`);
    const loads = await count(page, "loads");
    await page.setInputFiles("#files", ["lit-texture-mapping.json", "uv-grid.png"]
      .map((f) => join(out, f)));
    await page.waitForFunction((n) => Number(document.body.dataset.loads) > n, loads, { timeout: 60000 });
    results.lit_texture_message = await text(page, "message");
    await settle(page);
    await shot(page, "lit-texture-mapping.png");
    await page.close();
  }

  step("shadows near a black hole, from the file dialog");
  {
    // Bodies beside the hole shadowing each other (tests/data/hole-shadows.json): the page casts
    // their shadows along the curved paths itself, as the native program does.
    const page = await open(`scene=street&${still}`);
    const loads = await count(page, "loads");
    const chosen = Date.now();
    await page.setInputFiles("#files", [join(site, "..", "tests/data/hole-shadows.json")]);
    await page.waitForFunction((n) => Number(document.body.dataset.loads) > n, loads, { timeout: 60000 });
    results.hole_shadows_message = await text(page, "message");
    await settle(page, 1);
    results.hole_shadows_ms = Date.now() - chosen;  // until its first frame is drawn
    await settle(page);
    await shot(page, "hole-shadows.png");
    await page.close();
  }

  step("the spectrum table's columns the page fits");
  {
    const page = await open(`scene=street&${still}`, 1);
    results.columns = await page.evaluate(() => {
      const columns = {};
      for (const [l, j, i] of [[1, 7, 40], [2, 62, 0], [0, 12, 48], [0, 0, 0]])
        columns[`${l},${j},${i}`] = JSON.parse(window.lightcone.ccall("lc_table_column", "string",
          ["number", "number", "number"], [l, j, i]));
      return columns;
    });
    await page.close();
  }

  step("the frame rate on street.json at 640x360, flying");
  {
    const page = await open("scene=street", 5);
    const [frames0, t0] = await page.evaluate(() => [Number(document.body.dataset.frames), performance.now()]);
    await page.waitForTimeout(5000);
    const [frames1, t1] = await page.evaluate(() => [Number(document.body.dataset.frames), performance.now()]);
    results.fps = (frames1 - frames0) / ((t1 - t0) / 1000);
    // And `lightcone view --benchmark 100` in the page: the same scripted flight, draws alone.
    results.benchmark = await page.evaluate(() => JSON.parse(window.lightcone.ccall("lc_benchmark",
      "string", ["number", "number", "number"], [100, 640, 360])));
    await page.close();
  }
} finally {
  await writeFile(join(out, "results.json"), JSON.stringify(results, null, 1));
  await browser.close();
  server.close();
}
step(`done: ${JSON.stringify({ load_ms: results.load_ms, fps: results.fps })}`);
