#!/usr/bin/env python3
"""scripts/performance-page on a copy of docs/performance/: --update takes a Google Benchmark run's
figures into the rows that name it (and only those), and hostile input ends in exit 2 with the
file and key named, never a traceback.

Usage: test_performance_page.py [REPO_ROOT]   (ctest: docs.performance_page_update)
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
SCRIPT = os.path.join(ROOT, "scripts", "performance-page")


def bench_entry(name, **fields):
    entry = {"name": name, "family_index": 0, "per_family_instance_index": 0, "run_name": name,
             "run_type": "iteration", "repetitions": 1, "repetition_index": 0, "threads": 1, "iterations": 1,
             "real_time": 1.0e9, "cpu_time": 1.0e6, "time_unit": "ns"}
    entry.update(fields)
    return entry


def ratios(p50, p99, cpu50, cpu99):
    return {"p50_vs_nothing_paired": p50, "p99_vs_nothing_paired": p99, "cpu_p50_us_vs_nothing_paired": cpu50,
            "cpu_p99_us_vs_nothing_paired": cpu99}


class PerformancePage(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="performance-page-")
        self.root = self.tmp
        self.data = os.path.join(self.tmp, "docs", "performance")
        self.page = os.path.join(self.tmp, "docs", "performance.md")
        shutil.copytree(os.path.join(ROOT, "docs", "performance"), self.data)
        shutil.copy(os.path.join(ROOT, "docs", "performance.md"), self.page)
        os.makedirs(os.path.join(self.tmp, "out", "bench"))

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def run_page(self, *args):
        r = subprocess.run([sys.executable, SCRIPT, "--root", self.root, "--data", self.data, "--page", self.page]
                           + list(args), stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
        self.assertNotIn("Traceback", r.stdout + r.stderr)
        return r

    def section(self, name):
        with open(os.path.join(self.data, name + ".json"), encoding="utf-8") as f:
            return json.load(f)

    def row(self, section, what):
        return next(r for r in self.section(section)["rows"] if r["what"] == what)

    def write(self, path, content):
        mode = "wb" if isinstance(content, bytes) else "w"
        with open(path, mode) as f:
            f.write(content if isinstance(content, (bytes, str)) else json.dumps(content))
        return path

    def test_the_copy_agrees_and_a_change_is_found(self):
        self.assertEqual(self.run_page("--check").returncode, 0)
        with open(self.page, "a") as f:
            f.write("a line nobody generated\n")
        r = self.run_page("--check")
        self.assertEqual(r.returncode, 1)
        self.assertIn("+++", r.stdout)
        self.assertIn("a line nobody generated", r.stdout)

    def test_update_takes_the_run_into_its_rows_and_the_page(self):
        before = {name: self.section(name) for name in ("recording", "display")}
        untouched = self.row("monitoring", "nothing")
        run = {"context": {"date": "2031-02-03T10:00:00+00:00", "host_name": "test"},
               "benchmarks": [
                   # the plain run, its name with Google Benchmark's /iterations:1
                   bench_entry("AdmittanceTick/topic_hz/iterations:1", **ratios(1.234, 0.5, 1.111, 0.987)),
                   # repetitions: the median aggregate wins over the runs and the mean
                   bench_entry("AdmittanceTick/topic_echo/repeats:3", **ratios(9, 9, 9, 9)),
                   bench_entry("AdmittanceTick/topic_echo/repeats:3_mean", run_type="aggregate",
                               run_name="AdmittanceTick/topic_echo/repeats:3", aggregate_name="mean",
                               **ratios(8, 8, 8, 8)),
                   bench_entry("AdmittanceTick/topic_echo/repeats:3_median", run_type="aggregate",
                               run_name="AdmittanceTick/topic_echo/repeats:3", aggregate_name="median",
                               **ratios(1.5, 2.25, 3.0, 0.125)),
                   # a name that "nothing" is a prefix of: not the "nothing" row's
                   bench_entry("AdmittanceTick/nothing_again/iterations:1", **ratios(2, 2, 2, 2)),
                   # failed: its row keeps its figures
                   bench_entry("AdmittanceTick/bridge_all/iterations:1", error_occurred=True,
                               error_message="the bridge did not start"),
                   bench_entry("RecordDemo/all_topics/iterations:1", MB_per_s=300.0),
               ]}
        bench = self.write(os.path.join(self.tmp, "out", "bench", "monitor.json"), run)
        bridge = self.row("monitoring", "`bridge` + Foxglove client on every topic")
        r = self.run_page("--update", bench, "--machine", "test box")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("failed in this run: the bridge did not start", r.stderr)

        hz = self.row("monitoring", "`topic hz`")
        self.assertEqual((hz["wall"], hz["cpu"], hz["machine"], hz["date"]),
                         ("1.23x / 0.50x", "1.11x / 0.99x", "same", "2031-02-03"))
        echo = self.row("monitoring", "`topic echo`")
        self.assertEqual((echo["wall"], echo["cpu"], echo["machine"], echo["date"]),
                         ("1.50x / 2.25x", "3.00x / 0.12x", "test box", "2031-02-03"))
        again = self.row("monitoring", "nothing, again (the noise floor)")
        self.assertEqual((again["wall"], again["machine"], again["date"]), ("2.00x / 2.00x", "test box", "2031-02-03"))
        # rows the run has nothing for keep everything; a "same" after a changed row names its
        # machine again, and one after an unchanged row stays
        self.assertEqual(self.row("monitoring", "nothing"), untouched)
        self.assertEqual(self.row("monitoring", "`bridge` + Foxglove client on every topic"), bridge)
        hz_prompt = self.row("monitoring", "`topic hz --prompt`")
        self.assertEqual(hz_prompt["machine"], untouched["machine"])
        self.assertNotEqual(hz_prompt["date"], "2031-02-03")
        for name, section in before.items():
            self.assertEqual(self.section(name), section, name)

        with open(self.page, encoding="utf-8") as f:
            page = f.read()
        self.assertIn("| `topic hz` | within 5 % | 1.23x / 0.50x | 1.11x / 0.99x | same | 2031-02-03 |", page)
        self.assertIn("| `topic echo` | within 5 % | 1.50x / 2.25x | 3.00x / 0.12x | test box | 2031-02-03 |", page)
        self.assertEqual(self.run_page("--check").returncode, 0)

        # The same run again changes nothing; a run no row names is said so, and changes nothing.
        with open(os.path.join(self.data, "monitoring.json"), encoding="utf-8") as f:
            monitoring = f.read()
        self.assertEqual(self.run_page("--update", bench, "--machine", "test box").returncode, 0)
        other = self.write(os.path.join(self.tmp, "out", "bench", "kernel.json"),
                           {"benchmarks": [bench_entry("BM_Tick/iterations:1")]})
        r = self.run_page("--update", other)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("no row takes its figures from out/bench/kernel.json", r.stderr)
        with open(os.path.join(self.data, "monitoring.json"), encoding="utf-8") as f:
            self.assertEqual(f.read(), monitoring)

    def index_sections(self):
        """The sections the copied index lists."""
        with open(os.path.join(self.data, "index.json")) as f:
            return json.load(f)["sections"]

    def test_hostile_data(self):
        def edit(name, change):
            def apply():
                path = os.path.join(self.data, name + ".json")
                with open(path, encoding="utf-8") as f:
                    value = json.load(f)
                change(value)
                self.write(path, value)
            return apply

        def raw(name, content):
            return lambda: self.write(os.path.join(self.data, name + ".json"), content)

        def set_source_format(value):
            value["rows"][1]["source"]["cells"]["wall"]["format"] = "{0.__class__}"

        cases = [
            ("not JSON", raw("recording", "{\"title\": "), "recording.json", "not valid JSON"),
            ("not UTF-8", raw("display", b"{\"title\": \"\xff\"}"), "display.json", "UTF-8"),
            ("NaN", raw("display", "{\"title\": NaN}"), "display.json", "NaN"),
            ("nested deep", raw("display", "[" * 100000 + "]" * 100000), "display.json", ""),
            ("a list", raw("monitoring", "[]"), "monitoring.json", "should be an object"),
            ("duplicate key", raw("monitoring", "{\"title\": \"a\", \"title\": \"b\"}"), "monitoring.json",
             "'title'"),
            ("rows missing", edit("recording", lambda v: v.pop("rows")), "recording.json", "rows: missing"),
            ("rows a string", edit("recording", lambda v: v.update(rows="all")), "recording.json", "rows:"),
            ("cell missing", edit("display", lambda v: v["rows"][2].pop("goal")), "display.json",
             "rows[2].goal: missing"),
            ("cell a number", edit("display", lambda v: v["rows"][0].update(figure=2)), "display.json",
             "rows[0].figure: should be a string"),
            ("unknown key", edit("display", lambda v: v["rows"][0].update(figur="x")), "display.json",
             "rows[0].figur: unknown key"),
            ("column not an object", edit("display", lambda v: v["columns"].append("peer")), "display.json",
             "columns[5]"),
            ("format", edit("monitoring", set_source_format), "monitoring.json",
             "rows[1].source.cells.wall.format"),
            ("source of no column", edit("monitoring", lambda v: v["rows"][0]["source"]["cells"].update(x={
                "field": "p50_us"})), "monitoring.json", "rows[0].source.cells.x"),
            ("section missing", lambda: os.remove(os.path.join(self.data, "display.json")), "index.json", "display"),
            ("section unlisted", raw("extra", "{}"), "index.json", "extra.json"),
            ("sections not a list", edit("index", lambda v: v.update(sections="recording")), "index.json",
             "sections"),
            ("section a path", edit("index", lambda v: v["sections"].append("../x")), "index.json",
             "sections[%d]" % len(self.index_sections())),
        ]
        for label, damage, file, key in cases:
            with self.subTest(label):
                self.tearDown()
                self.setUp()
                damage()
                for args in (["--check"], []):
                    r = self.run_page(*args)
                    self.assertEqual(r.returncode, 2, "%s: %s%s" % (label, r.stdout, r.stderr))
                    self.assertIn(file, r.stderr)
                    self.assertIn(key, r.stderr)
                    self.assertEqual(r.stderr.count("\n"), 1, r.stderr)

    def test_hostile_benchmark_runs(self):
        bench = os.path.join(self.tmp, "out", "bench", "monitor.json")
        cases = [
            ("not JSON", "{\"benchmarks\": [", "not valid JSON"),
            ("a list", [], "should be an object"),
            ("no benchmarks", {"context": {}}, "benchmarks: missing"),
            ("benchmarks an object", {"benchmarks": {}}, "benchmarks: should be a list"),
            ("an entry without a name", {"benchmarks": [{"real_time": 1}]}, "benchmarks[0].name: missing"),
            ("a name that is a number", {"benchmarks": [{"name": 7}]}, "benchmarks[0].name: should be a string"),
            ("context a list", {"context": [], "benchmarks": []}, "context: should be an object"),
            ("a counter that is text", {"benchmarks": [bench_entry(
                "AdmittanceTick/topic_hz/iterations:1", **dict(ratios(1, 1, 1, 1), p50_vs_nothing_paired="fast"))]},
             "benchmarks[0].p50_vs_nothing_paired: should be a finite number"),
            ("a counter missing", {"benchmarks": [bench_entry(
                "AdmittanceTick/topic_hz/iterations:1", p50_vs_nothing_paired=1.0)]},
             "benchmarks[0].p99_vs_nothing_paired: missing"),
            ("error_occurred text", {"benchmarks": [bench_entry("x", error_occurred="yes")]},
             "benchmarks[0].error_occurred"),
        ]
        with open(os.path.join(self.data, "monitoring.json"), encoding="utf-8") as f:
            monitoring = f.read()
        for label, content, key in cases:
            with self.subTest(label):
                self.write(bench, content)
                r = self.run_page("--update", bench)
                self.assertEqual(r.returncode, 2, "%s: %s%s" % (label, r.stdout, r.stderr))
                self.assertIn("out/bench/monitor.json", r.stderr)
                self.assertIn(key, r.stderr)
                self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
                with open(os.path.join(self.data, "monitoring.json"), encoding="utf-8") as f:
                    self.assertEqual(f.read(), monitoring)  # nothing written on bad input
        r = self.run_page("--update", os.path.join(self.tmp, "out", "bench", "absent.json"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("absent.json: cannot read", r.stderr)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
