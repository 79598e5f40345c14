// Loads the bridge's web dashboard in Debian's headless Chromium (driven by playwright-core),
// waits until it shows live data (table rows none of them silent, plot points, video frames),
// takes a screenshot and prints what the page's DOM holds as JSON. (Under a loaded CI machine the
// page once marked every row silent at the moment it was read, 3 s without a report, while the
// plots and the video went on: a row is now waited for until it reports again, within the
// timeout, not read in that moment.)
//   node dashboard_check.mjs http://127.0.0.1:PORT/ SCREENSHOT.png SECONDS
import { chromium } from "playwright-core";

const [url, screenshot, seconds] = process.argv.slice(2);
const browser = await chromium.launch({
  executablePath: process.env.WYSIWYF_CHROMIUM ?? "/usr/bin/chromium",
  args: ["--no-sandbox", "--disable-gpu"],
});
let code = 0;
try {
  const page = await browser.newPage({ viewport: { width: 1400, height: 1000 } });
  const errors = [];
  page.on("pageerror", (e) => errors.push(String(e)));
  await page.goto(url);
  try {
    await page.waitForFunction(
      () =>
        document.querySelectorAll("#components tbody tr").length > 0 &&
        document.querySelectorAll("#components tbody td.state-silent").length === 0 &&
        [...document.querySelectorAll(".plot")].some((p) => Number(p.dataset.points) >= 20) &&
        Number(document.getElementById("video").dataset.frames) >= 3,
      null,
      { timeout: Number(seconds) * 1000, polling: 200 },
    );
  } catch (e) {
    code = 1; // report what the page got so far
  }
  const dom = await page.evaluate(() => ({
    connection: document.getElementById("connection").textContent,
    domain: document.getElementById("domain").textContent,
    mode: document.getElementById("mode").textContent,
    components: [...document.querySelectorAll("#components tbody tr")].map((tr) => {
      const c = [...tr.children].map((td) => td.textContent);
      return { instance: c[0], type: c[1], process: c[2], state: c[3], rate: c[4], p99_us: c[6], problem: c[11] };
    }),
    plots: [...document.querySelectorAll(".plot")].map((p) => ({
      plot: p.dataset.plot,
      points: Number(p.dataset.points),
      last: p.dataset.last === undefined ? null : Number(p.dataset.last),
      canvas: !!p.querySelector("canvas"),
    })),
    video: {
      frames: Number(document.getElementById("video").dataset.frames),
      width: document.getElementById("video").naturalWidth,
      height: document.getElementById("video").naturalHeight,
    },
  }));
  dom.page_errors = errors;
  await page.screenshot({ path: screenshot, fullPage: true });
  process.stdout.write(JSON.stringify(dom) + "\n");
} finally {
  await browser.close();
}
process.exit(code);
