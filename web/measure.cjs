// Measures Glint's page in headless Chromium (SwiftShader's WebGPU): for each
// scene, the first image's time from page load (the kernels' compile
// included), then over the next 60 s the frame time and the samples per
// second while up to 64 accumulate, as the page's bar shows them. Serve the page first (web/serve.sh), then:
//   GLINT_PLAYWRIGHT=target/web-test/node/node_modules/playwright-core \
//     node web/measure.cjs http://127.0.0.1:8080/ showcase.toml whitted1980.toml
const { chromium } = require(require("path").resolve(process.env.GLINT_PLAYWRIGHT));

const [url, ...scenes] = process.argv.slice(2);

async function measure(browser, scene) {
  const page = await browser.newPage({ viewport: { width: 960, height: 600 } });
  await page.goto(`${url}#scene=${scene}&spp=64`);
  const deadline = Date.now() + 600_000;
  let s = {};
  while (Date.now() < deadline) {
    s = JSON.parse((await page.textContent("#glint-state")) || "{}");
    if (s.fatal) throw new Error(s.fatal);
    if (s.first_image_ms) break;
    await page.waitForTimeout(500);
  }
  const first = s;
  await page.waitForTimeout(60_000);
  s = JSON.parse(await page.textContent("#glint-state"));
  await page.close();
  const rate = (s.samples - first.samples) / 60;
  return `${scene}: ${s.render_size?.join("x")}, first image ${(s.first_image_ms / 1000).toFixed(1)} s, ${s.frame_ms?.toFixed(0)} ms/frame, ${rate.toFixed(2)} samples/s`;
}

(async () => {
  const browser = await chromium.launch({
    executablePath: require("child_process").execFileSync(require("path").join(__dirname, "../.ci/chromium"), ["--which"]).toString().trim(),
    headless: true,
    args: ["--headless=new", "--no-sandbox", "--enable-unsafe-webgpu", "--disable-gpu-sandbox", "--use-angle=vulkan", "--enable-features=Vulkan"],
  });
  for (const scene of scenes) console.log(await measure(browser, scene));
  await browser.close();
})().catch((e) => {
  console.error(e.message);
  process.exitCode = 1;
});
