// The amrvk widget in a real page (tests/browser/widget_notebook.sh starts the notebook server):
// headless Chromium runs the notebook's cells through the Notebook's own front end, then checks
// what a user sees and does. argv: URL SCRATCH. Exit 0 when every check holds; each failed
// check is one "FAIL:" line. Waits on the page's state, never a fixed sleep.
const puppeteer = require("puppeteer-core");
const [url, dir] = process.argv.slice(2);
let failed = 0;
const check = (ok, what) => { console.log(`${ok ? "ok" : "FAIL"}: ${what}`); if (!ok) failed++; };

(async () => {
  const browser = await puppeteer.launch({
    executablePath: "/usr/bin/chromium", headless: true,
    args: ["--no-sandbox", "--disable-gpu", "--window-size=1200,900"],
  });
  try {
    const page = await browser.newPage();
    await page.setViewport({ width: 1200, height: 900 });
    page.setDefaultTimeout(180000);
    await page.goto(url, { waitUntil: "networkidle2" });
    await page.waitForFunction(() => window.Jupyter && Jupyter.notebook && Jupyter.notebook.kernel &&
                                      Jupyter.notebook.kernel.is_connected());
    await page.evaluate(() => Jupyter.notebook.execute_cells([0]));
    // The first picture, then the refined one: the image at its own size (not stretched to the
    // cell), the status line whole (point 13), the count reached (points 12, 15).
    await page.waitForFunction(() => {
      const s = [...document.querySelectorAll(".widget-label, .jupyter-widgets.widget-label")]
        .map((e) => e.textContent);
      return s.some((t) => /^16\/16 spp, mean standard error/.test(t));
    });
    const seen = await page.evaluate(() => {
      const img = document.querySelector("img.widget-image");
      const label = [...document.querySelectorAll(".widget-label")].find((e) => /spp/.test(e.textContent));
      const r = img.getBoundingClientRect();
      return { natural: [img.naturalWidth, img.naturalHeight], shown: [r.width, r.height], text: label.textContent,
               whole: label.scrollWidth <= label.clientWidth + 1, labelWidth: label.clientWidth,
               sliders: document.querySelectorAll(".ui-slider-handle, .noUi-handle, input[type=range], .slider").length };
    });
    console.log(JSON.stringify(seen));
    check(seen.natural[0] === 96 && seen.natural[1] === 64, `the image is 96x64 (${seen.natural})`);
    check(Math.round(seen.shown[0]) === 96 && Math.round(seen.shown[1]) === 64, `shown at its own size (${seen.shown})`);
    check(seen.whole && seen.labelWidth > 72, `the status line is whole (${seen.labelWidth} px: "${seen.text}")`);
    const before = await page.evaluate(() => document.querySelector("img.widget-image").src);
    // The azimuth slider by keyboard: focus its handle, ten steps right (point 11: small moves).
    const handle = await page.$(".widget-slider .ui-slider-handle");  // the first: azimuth
    check(handle !== null, "the azimuth slider has a handle to focus");
    if (handle) {
      await handle.focus();
      for (let i = 0; i < 10; ++i) await page.keyboard.press("ArrowRight");
    }
    await page.waitForFunction((old) => {
      const img = document.querySelector("img.widget-image");
      const s = [...document.querySelectorAll(".widget-label")].map((e) => e.textContent);
      return img.src !== old && s.some((t) => /^16\/16 spp/.test(t));
    }, {}, before);
    // The kernel's view of it: the renderer path-traces (never left in dvr), the camera is the
    // first one orbited by the slider's value, the count is the image's.
    await page.evaluate(() => Jupyter.notebook.execute_cells([1]));
    await page.waitForFunction(() => /STATE /.test(document.querySelectorAll(".output_area")[1]?.textContent || ""));
    const text = await page.evaluate(() => document.querySelectorAll(".output_area")[1].textContent);
    const state = JSON.parse(text.slice(text.indexOf("STATE ") + 6).trim().split("\n")[0]);
    console.log(JSON.stringify(state));
    check(state.mode === "ms", `the renderer path-traces (mode ${state.mode})`);
    check(state.azimuth > 0, `the slider moved (azimuth ${state.azimuth})`);
    check(state.eye.every((v, i) => Math.abs(v - state.expected_eye[i]) <= 1e-9 * (1 + Math.abs(v))),
          "the camera is the first one orbited by the slider's value");
    check(state.spp === 16 && state.status.startsWith("16/16 spp"), `the count is the image's (${state.status})`);
    await page.screenshot({ path: `${dir}/widget.png`, fullPage: true });
    console.log(`screenshot: ${dir}/widget.png`);
  } finally {
    await browser.close();
  }
  process.exit(failed ? 1 : 0);
})().catch((e) => { console.log(`FAIL: ${e.message.split("\n")[0]}`); process.exit(1); });
