// Drives Glint's page in headless Chromium with real input events on its
// canvas, as tests/browser.rs asks: node drive.cjs URL OUT_DIR FILES_DIR.
// Writes OUT_DIR/results.json and the PNGs the page downloads; every wait is
// bounded, and a page without WebGPU is a failure.
const { chromium } = require(process.env.GLINT_PLAYWRIGHT);
const fs = require("fs");
const path = require("path");

const [url, out, files] = process.argv.slice(2);
const results = {};
const log = (...parts) => console.log(new Date().toISOString().slice(11, 23), ...parts);

async function main() {
  const browser = await chromium.launch({
    executablePath: "/usr/bin/chromium",
    headless: true,
    // ANGLE on Vulkan composites the WebGPU canvas: with the default GL
    // compositor, presenting to it breaks the device's read-backs here.
    args: ["--headless=new", "--no-sandbox", "--enable-unsafe-webgpu", "--disable-gpu-sandbox", "--use-angle=vulkan", "--enable-features=Vulkan"],
    timeout: 60_000,
  });
  try {
    const page = await browser.newPage({ viewport: { width: 960, height: 600 }, acceptDownloads: true });
    page.on("console", (m) => log("page:", m.text()));
    page.on("pageerror", (e) => log("page error:", e.message));
    const state = async () => JSON.parse((await page.textContent("#glint-state")) || "{}");
    const until = async (what, test, seconds) => {
      const deadline = Date.now() + seconds * 1000;
      let s = {};
      while (Date.now() < deadline) {
        s = await state();
        if (s.fatal) throw new Error(`the page cannot run Glint: ${s.fatal}`);
        if (test(s)) return s;
        await page.waitForTimeout(200);
      }
      throw new Error(`no ${what} within ${seconds} s; the page's state: ${JSON.stringify(s)}`);
    };
    const centre = (r) => [(r[0] + r[2]) / 2, (r[1] + r[3]) / 2];
    const savePng = async (s, name) => {
      const [x, y] = centre(s.buttons.save_png);
      const [download] = await Promise.all([page.waitForEvent("download", { timeout: 60_000 }), page.mouse.click(x, y)]);
      const file = path.join(out, name);
      await download.saveAs(file);
      log("saved", file, "as", download.suggestedFilename());
      return { file, suggested: download.suggestedFilename() };
    };
    const drop = async (names) => {
      const contents = names.map((n) => [n, Array.from(fs.readFileSync(path.join(files, n)))]);
      const transfer = await page.evaluateHandle((contents) => {
        const t = new DataTransfer();
        for (const [name, bytes] of contents) t.items.add(new File([new Uint8Array(bytes)], name));
        return t;
      }, contents);
      for (const type of ["dragenter", "dragover", "drop"]) {
        await page.dispatchEvent("#glint", type, { dataTransfer: transfer });
      }
    };

    // One sample per pixel, through its centre, as the native image is traced.
    await page.goto(`${url}#scene=showcase.toml&spp=1`, { timeout: 60_000 });
    let s = await until("first image of the showcase", (s) => s.scene === "showcase.toml" && s.converged && s.image_rect, 600);
    results.first_image_ms = s.first_image_ms;
    results.frame_ms = s.frame_ms;
    results.render_size = s.render_size;
    results.showcase = await savePng(s, "showcase.png");

    // Probe a pixel: Ctrl-click in the image.
    const [ix, iy] = centre(s.image_rect);
    await page.keyboard.down("Control");
    await page.mouse.click(ix, iy + (s.image_rect[3] - s.image_rect[1]) / 8);
    await page.keyboard.up("Control");
    s = await until("ray tree of the probed pixel", (t) => t.tree.length > 1, 300);
    results.tree = s.tree;

    // Drop an NFF scene, whose light is in view.
    await drop(["dropped.nff"]);
    s = await until("image of the dropped NFF", (t) => t.scene === "dropped.nff" && t.converged && t.lights[0], 600);
    results.dropped = { scene: s.scene, errors: s.errors, link: s.link };
    results.dropped_png = await savePng(s, "dropped.png");

    // Edit its light through the UI: drag the light's marker, slowly enough
    // that the page sees the press, the moves and the release in frames of
    // their own.
    const [lx, ly] = s.lights[0];
    const before = s;
    await page.mouse.move(lx, ly);
    await page.waitForTimeout(300);
    await page.mouse.down();
    for (let step = 1; step <= 10; step++) {
      await page.mouse.move(lx - 6 * step, ly + 3 * step);
      await page.waitForTimeout(150);
    }
    await page.waitForTimeout(300);
    await page.mouse.up();
    s = await until("image with the light moved", (t) => t.converged && JSON.stringify(t.lights) !== JSON.stringify(before.lights), 300);
    results.light_moved = { from: [lx, ly], to: s.lights[0], link_before: before.link, link_after: s.link };
    results.moved = await savePng(s, "light-moved.png");

    // Bad files, each a message in the page.
    results.bad = {};
    for (const name of ["broken.toml", "empty.nff", "garbage.obj", "cube.obj", "notes.mtl"]) {
      await drop([name]);
      const said = (t) => [...t.errors, ...t.warnings].filter((e) => e.includes(name));
      s = await until(`message about ${name}`, (t) => said(t).length > 0, 120);
      results.bad[name] = said(s);
    }
    results.shown = s.scene;
  } finally {
    fs.writeFileSync(path.join(out, "results.json"), JSON.stringify(results, null, 1));
    await browser.close();
  }
}

main().then(
  () => log("done"),
  (e) => {
    log("failed:", e.message);
    process.exitCode = 1;
  },
);
