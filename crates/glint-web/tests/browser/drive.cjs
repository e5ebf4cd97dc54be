// Drives Glint's page in headless Chromium with real input events on its
// canvas, as tests/browser.rs asks: node drive.cjs URL OUT_DIR FILES_DIR LINK.
// Writes OUT_DIR/results.json and the files the page downloads; every wait
// is bounded (against a hang, not to time anything), and a page without
// WebGPU is a failure.
const { chromium } = require(process.env.GLINT_PLAYWRIGHT);
const fs = require("fs");
const path = require("path");

const [url, out, files, link] = process.argv.slice(2);
const results = {};
const log = (...parts) => console.log(new Date().toISOString().slice(11, 23), ...parts);

async function main() {
  const browser = await chromium.launch({
    executablePath: require("child_process").execFileSync(require("path").join(__dirname, "../../../../.ci/chromium"), ["--which"]).toString().trim(),
    headless: true,
    // ANGLE on Vulkan composites the WebGPU canvas: with the default GL
    // compositor, presenting to it breaks the device's read-backs here.
    args: ["--headless=new", "--no-sandbox", "--enable-unsafe-webgpu", "--disable-gpu-sandbox", "--use-angle=vulkan", "--enable-features=Vulkan"],
    timeout: 60_000,
  });
  try {
    const open = async (viewport) => {
      const page = await browser.newPage({ viewport, acceptDownloads: true });
      page.on("console", (m) => log("page:", m.text()));
      page.on("pageerror", (e) => log("page error:", e.message));
      // Intercepts file pickers from the start: a listener added only when
      // one is awaited comes too late for the page's picker.
      page.on("filechooser", () => {});
      return page;
    };
    const page = await open({ width: 960, height: 600 });
    const state = async (p = page) => JSON.parse((await p.textContent("#glint-state")) || "{}");
    const until = async (what, test, seconds, p = page) => {
      const deadline = Date.now() + seconds * 1000;
      let s = {};
      while (Date.now() < deadline) {
        s = await state(p);
        if (s.fatal) throw new Error(`the page cannot run Glint: ${s.fatal}`);
        if (test(s)) return s;
        await p.waitForTimeout(200);
      }
      throw new Error(`no ${what} within ${seconds} s; the page's state: ${JSON.stringify(s)}`);
    };
    const centre = (r) => [(r[0] + r[2]) / 2, (r[1] + r[3]) / 2];
    // Clicks one of the bar's buttons and waits for what it makes happen.
    const click = async (s, button, event, p = page) => {
      const [x, y] = centre(s.buttons[button]);
      const [happened] = await Promise.all([p.waitForEvent(event, { timeout: 60_000 }), p.mouse.click(x, y)]);
      return happened;
    };
    const download = async (s, button, name, p = page) => {
      const file = path.join(out, name);
      const downloaded = await click(s, button, "download", p);
      await downloaded.saveAs(file);
      log("saved", file, "as", downloaded.suggestedFilename());
      return { file, suggested: downloaded.suggestedFilename() };
    };
    const savePng = (s, name, p = page) => download(s, "save_png", name, p);
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

    // Open an OBJ and its MTL through the file picker.
    const chooser = await click(s, "open", "filechooser");
    await chooser.setFiles(["picked.obj", "picked.mtl"].map((n) => path.join(files, n)));
    s = await until("image of the picked OBJ", (t) => t.scene === "picked.obj" && t.converged, 600);
    results.picked = { scene: s.scene, errors: s.errors, warnings: s.warnings };
    results.picked_png = await savePng(s, "picked.png");

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
    results.moved_toml = await download(s, "save_toml", "light-moved.toml");

    // Bad files, each a message in the page.
    results.bad = {};
    for (const name of ["broken.toml", "empty.nff", "garbage.obj", "cube.obj", "notes.mtl"]) {
      await drop([name]);
      const said = (t) => [...t.errors, ...t.warnings].filter((e) => e.includes(name));
      s = await until(`message about ${name}`, (t) => said(t).length > 0, 120);
      results.bad[name] = said(s);
    }
    results.shown = s.scene;

    // A shared link: scene, camera and samples per pixel in the fragment, in
    // a page of its own, smaller, so that its samples come sooner: in about
    // 3 s each here, where they once took minutes (docs/performance.md).
    const linked = await open({ width: 640, height: 400 });
    await linked.goto(`${url}#${link}`, { timeout: 60_000 });
    const first = await until("first image of the link", (t) => t.samples >= 1, 600, linked);
    const sampled = Date.now();
    s = await until("all samples of the link", (t) => t.converged && t.samples >= first.target_samples, 300, linked);
    results.link = {
      link: s.link,
      errors: s.errors,
      samples: s.samples,
      render_size: s.render_size,
      first_image_ms: first.first_image_ms,
      samples_per_second: (s.samples - first.samples) / ((Date.now() - sampled) / 1000),
    };
    results.link_png = await savePng(s, "link.png", linked);
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
