// Loads a run report's index.html in Debian's headless Chromium (driven by playwright-core) and
// checks that its video plays there: the <video> gets to HAVE_CURRENT_DATA (readyState >= 2)
// with a duration, seeks to its middle without a MediaError, and the frame it shows there, drawn
// into a canvas, is an image (not one flat colour). Takes a screenshot of the page and prints what
// it found as JSON; exits 1 if the video does not play.
//   node report_video.mjs file:///.../index.html SCREENSHOT.png
import { chromium } from "playwright-core";

const [url, screenshot] = process.argv.slice(2);
const browser = await chromium.launch({
  executablePath: process.env.WYSIWYF_CHROMIUM ?? "/usr/bin/chromium",
  // file: pages are each their own origin; this flag lets the page read its video's pixels
  args: ["--no-sandbox", "--disable-gpu", "--allow-file-access-from-files"],
});
let code = 0;
try {
  const page = await browser.newPage({ viewport: { width: 1200, height: 900 } });
  await page.goto(url);
  const found = await page.evaluate(async () => {
    const v = document.querySelector("video");
    if (!v) return { problem: "the page has no <video>" };
    const error = () => (v.error ? `MediaError ${v.error.code} ${v.error.message}` : null);
    // Resolves when ready() holds, a MediaError came or 10 s passed.
    const until = (ready) =>
      new Promise((done) => {
        const start = performance.now();
        const poll = () => (ready() || v.error || performance.now() - start > 10000 ? done() : setTimeout(poll, 50));
        poll();
      });
    v.muted = true;
    v.preload = "auto";
    v.load();
    await until(() => v.readyState >= 2);
    const loaded = { readyState: v.readyState, duration: v.duration, error: error() };
    if (loaded.readyState < 2 || !(loaded.duration > 0) || loaded.error) return { src: v.currentSrc, loaded };
    const seeked = new Promise((done) => v.addEventListener("seeked", done, { once: true }));
    v.currentTime = v.duration / 2;
    await Promise.race([seeked, new Promise((done) => setTimeout(done, 10000))]);
    await until(() => v.readyState >= 2 && !v.seeking);
    const canvas = document.createElement("canvas");
    canvas.width = v.videoWidth;
    canvas.height = v.videoHeight;
    const g = canvas.getContext("2d");
    g.drawImage(v, 0, 0);
    const px = g.getImageData(0, 0, canvas.width, canvas.height).data;
    let sum = 0, sum2 = 0;
    for (let i = 0; i < px.length; i += 4) {
      const y = (px[i] + px[i + 1] + px[i + 2]) / 3;
      sum += y;
      sum2 += y * y;
    }
    const n = px.length / 4;
    v.scrollIntoView();
    return {
      src: v.currentSrc,
      loaded,
      after_seek: { currentTime: v.currentTime, readyState: v.readyState, seeking: v.seeking, error: error() },
      frame: { width: v.videoWidth, height: v.videoHeight, mean: sum / n, stddev: Math.sqrt(Math.max(0, sum2 / n - (sum / n) ** 2)) },
    };
  });
  const a = found.after_seek;
  if (found.problem) code = 1;
  else if (!a || a.error || a.readyState < 2 || a.seeking || !(found.loaded.duration > 0)) code = 1;
  else if (!(found.frame.width > 0) || !(found.frame.stddev > 2)) code = 1;
  await page.screenshot({ path: screenshot });
  process.stdout.write(JSON.stringify(found) + "\n");
} finally {
  await browser.close();
}
process.exit(code);
