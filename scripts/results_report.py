#!/usr/bin/env python3
"""Writes docs/RESULTS.md from the CSV files of scripts/results.

Two uses (called by scripts/results; standard library only):

  results_report.py --machine FILE.json
      describes this machine (CPU model, cores, memory, OS, compiler, load,
      date, git commit) into FILE.json, before the measurements start;

  results_report.py --data DIR --out docs/RESULTS.md --images docs/images/results [--quick]
      reads DIR/machine.json, DIR/commands.tsv (step, seconds, exit code,
      command), lut_accuracy.csv, render_frame_times.csv,
      projector_frame_times.csv, cluster_bench.csv, startup_times.csv,
      startup_pass_compile.csv, cie/cie_summary.csv,
      cie/cie_cases.csv, measured/measured_summary.csv, measured/measured_captures.csv,
      measured_aeronet/measured_summary.csv, eclipse/eclipse_zenith.csv,
      stress/stress_regions.csv, stress/stress_gpu.csv
      (a missing file leaves its section saying so), copies the PNG charts
      into --images and writes the markdown.
"""
import argparse
import csv
import datetime
import json
import math
import os
import platform
import shutil
import subprocess
import sys

# ---------------------------------------------------------------- machine


def default_sphere_nodes(rows):
    """The sphere-integral nodes of the project default's row of lut_accuracy.csv (the precompute's default,
    atmosphere/lut/precompute_options.h), which settings not named otherwise use."""
    for r in rows:
        if r.get("project_default") == "1":
            return r["sphere_samples"]
    return "24"


def run_text(args):
    try:
        return subprocess.run(args, capture_output=True, text=True, check=False).stdout.strip()
    except OSError:
        return ""


def describe_machine():
    cpu, flags = "unknown", ""
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                key, _, value = line.partition(":")
                if key.strip() == "model name" and cpu == "unknown":
                    cpu = value.strip()
                if key.strip() == "flags" and not flags:
                    flags = value
    except OSError:
        pass
    memory_gib = None
    try:
        with open("/proc/meminfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("MemTotal:"):
                    memory_gib = int(line.split()[1]) / 1024 / 1024
    except OSError:
        pass
    os_name = platform.system()
    try:
        with open("/etc/os-release", encoding="utf-8") as f:
            for line in f:
                if line.startswith("PRETTY_NAME="):
                    os_name = line.split("=", 1)[1].strip().strip('"')
    except OSError:
        pass
    commit = run_text(["git", "rev-parse", "--short", "HEAD"])
    dirty = bool(run_text(["git", "status", "--porcelain", "--untracked-files=no"]))
    return {
        "cpu": cpu,
        "cpu_simd": " ".join(x for x in ("avx2", "avx512f") if f" {x} " in f" {flags} "),
        "logical_cores": os.cpu_count(),
        "memory_gib": memory_gib,
        "os": f"{os_name}, Linux {platform.release()}",
        "compiler": run_text(["c++", "--version"]).splitlines()[0] if run_text(["c++", "--version"]) else "unknown",
        "load_average": os.getloadavg()[0] if hasattr(os, "getloadavg") else None,
        "date_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "commit": commit or "unknown",
        "uncommitted_changes": dirty,
    }


# ---------------------------------------------------------------- helpers


def read_csv(path):
    if not os.path.exists(path):
        return None
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def num(text):
    try:
        v = float(text)
        return v if math.isfinite(v) else None
    except (TypeError, ValueError):
        return None


def g(v, digits=3):
    """A number with `digits` significant digits; '–' when missing."""
    if v is None:
        return "–"
    if v == 0:
        return "0"
    if abs(v) >= 10 ** digits or abs(v) < 1e-3:
        return f"{v:.{digits - 1}e}".replace("e-0", "e-").replace("e+0", "e")
    return f"{v:.{digits}g}"


def f1(v):
    return "–" if v is None else f"{v:,.1f}".replace(",", " ")


def count(v):
    v = num(v)
    return "–" if v is None else f"{int(v):,}".replace(",", " ")


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


class Report:
    def __init__(self, data, out, images, quick):
        self.data, self.out, self.images, self.quick = data, out, images, quick
        self.lines = []
        self.machine = {}
        path = os.path.join(data, "machine.json")
        if os.path.exists(path):
            with open(path, encoding="utf-8") as f:
                self.machine = json.load(f)
        self.steps = {}
        path = os.path.join(data, "commands.tsv")
        if os.path.exists(path):
            with open(path, encoding="utf-8") as f:
                for line in f:
                    parts = line.rstrip("\n").split("\t")
                    if len(parts) == 4:
                        self.steps[parts[0]] = {"seconds": int(parts[1]), "rc": int(parts[2]), "command": parts[3]}
        self.gl = self.gl_renderer()

    def add(self, *text):
        self.lines.extend(text)

    def data_path(self, name):
        """How RESULTS.md (in docs/) names a data file."""
        full = os.path.join(self.data, name)
        rel = os.path.relpath(full, os.path.dirname(self.out) or ".")
        return f"[`{name}`]({rel})" if not self.quick else f"`{full}`"

    def gl_renderer(self):
        for name, column in (("render_frame_times.csv", "device"), ("lut_accuracy.csv", "device")):
            for row in self.csv(name) or []:
                if row.get(column) and not row[column].startswith("CPU"):
                    return row[column]
        return "unknown"

    def machine_line(self):
        m = self.machine
        cores = m.get("logical_cores")
        return (f"{m.get('cpu', 'unknown CPU')}, {cores} logical cores, GL: {self.gl}"
                f"{'; quick run' if self.quick else ''}")

    def csv(self, *path):
        """The rows of a CSV file of the data folder (None when missing)."""
        return read_csv(os.path.join(self.data, *path))

    def measured(self, key, *path):
        """A section's 'measured by' line (provenance), then the rows of its CSV file."""
        self.provenance(key)
        return self.csv(*path)

    def validation(self, key, summary_file, rows_file, what):
        """A validation's provenance line, its summary and its rows (key/ folder); (None, None) after saying
        which file is missing."""
        summary = self.measured(key, key, summary_file)
        rows = self.csv(key, rows_file)
        if not summary or not rows:
            self.add(f"*No {what} results ({summary_file} / {rows_file} missing).*", "")
            return None, None
        return summary, rows

    def provenance(self, key):
        """The 'measured by' line of a section: command, duration, machine."""
        s = self.steps.get(key)
        if not s:
            self.add(f"*Not run in this pass ({key}).*", "")
            return False
        status = "" if s["rc"] == 0 else f" — **exited with {s['rc']}**, see its log"
        self.add(f"Command: `{s['command']}` ({s['seconds']} s{status}). "
                 f"Machine: {self.machine_line()}.", "")
        return True

    def image(self, source, name, alt):
        src = os.path.join(self.data, source)
        if not os.path.exists(src):
            self.add(f"*(chart {source} missing: gnuplot not installed or the step failed)*", "")
            return
        os.makedirs(self.images, exist_ok=True)
        shutil.copyfile(src, os.path.join(self.images, name))
        rel = os.path.relpath(os.path.join(self.images, name), os.path.dirname(self.out) or ".")
        size_kb = os.path.getsize(src) / 1024
        if size_kb > 300:
            print(f"results_report: {name} is {size_kb:.0f} KB (over 300 KB)", file=sys.stderr)
        self.add(f"![{alt}]({rel})", "")

    # ------------------------------------------------------------ sections

    def header(self):
        m = self.machine
        self.add("# Results: accuracy, numerical stability and speed", "")
        if self.quick:
            self.add("> **Quick run** (`scripts/results --quick`): small tables, small frame sizes and a subset of",
                     "> the settings. It checks that the whole pipeline works; its figures are not the ones to quote.",
                     "> The full run is `scripts/results`.", "")
        self.add("Generated by `scripts/results" + (" --quick" if self.quick else "") + "` "
                 f"on {m.get('date_utc', 'an unknown date')} from commit `{m.get('commit', '?')}`"
                 + (" with uncommitted changes in the working tree" if m.get("uncommitted_changes") else "")
                 + ". Every figure on this page was measured on this machine:", "")
        mem = m.get("memory_gib")
        load = m.get("load_average")
        self.add(table(["", ""], [
            ["CPU", f"{m.get('cpu', 'unknown')} ({m.get('logical_cores', '?')} logical cores"
                    + (f"; {m['cpu_simd']}" if m.get("cpu_simd") else "") + ")"],
            ["memory", f"{mem:.1f} GiB" if mem else "unknown"],
            ["GL (renderer and GPU precompute)", f"`{self.gl}`"
             + (" (Mesa's CPU rasterizer: no GPU)" if "llvmpipe" in self.gl else "")],
            ["OS", m.get("os", "unknown")],
            ["compiler", f"{m.get('compiler', 'unknown')}, Release build"],
            ["load average when the run started", f"{load:.1f}" if load is not None else "unknown"],
        ]), "")
        total = sum(s["seconds"] for s in self.steps.values())
        self.add("Regenerate everything with `scripts/results` (full run) or `scripts/results --quick`; "
                 f"this run took {total / 60:.0f} min (per step: [below](#this-run)). Each section names "
                 "the command of its figures; the charts are in `docs/images/results/`, the data "
                 + ("in `" + self.data + "` (not committed)." if self.quick else
                    "in [`bench/results/`](../bench/results/)."), "")

    def headline(self):
        self.add("## Headline figures", "")
        items = []
        cie = self.csv("cie", "cie_summary.csv")
        suns = [num(r["sun_zenith_deg"]) for r in self.csv("cie", "cie_cases.csv") or []]
        span = f"sun zenith {g(min(suns))}–{g(max(suns))}°" if suns else "all sun positions"
        for r in cie or []:
            if r["variant"] == "as-is":
                items.append(f"Relative sky luminance L/Lz of `{r['preset']}` against the CIE standard clear sky "
                             f"(type 12), {r['points']} sky points, {span}: RMS difference "
                             f"{g(num(r['rms_type12']), 2)} (largest {g(num(r['max_abs_type12']), 2)}); "
                             f"30° or more from the sun RMS {g(num(r['rms_type12_far']), 2)} (largest "
                             f"{g(num(r['max_abs_type12_far']), 2)}); best-fitting CIE type {r['best_type']}.")
        stress = self.csv("stress", "stress_regions.csv")
        for r in stress or []:
            if r["model"] == "all" and r["region"] == "all":
                bad = sum(int(r[k]) for k in ("nan", "inf", "negative", "transmittance_above_1"))
                items.append(f"Numerical stability: {count(r['samples'])} configurations, {count(r['values'])} "
                             f"values, {bad} NaN/Inf/negative/T>1 on the CPU path.")
        pick = self.recommendation()
        if pick:
            items.append(pick)
        render = self.csv("render_frame_times.csv")
        if render:
            parts = []
            for r in render:
                if r["atmospheres"] in ("0", "3"):
                    parts.append((r["resolution"], r["projection"], r["atmospheres"], num(r["frame_ms"])))
            by_res = {}
            for res, proj, atm, ms in parts:
                by_res.setdefault((res, proj), {})[atm] = ms
            text = "; ".join(f"{res.replace('x', '×')} {proj.split()[0]} {f1(v.get('3'))} ms with 3 atmospheres "
                             f"({f1(v.get('0'))} ms bodies only)" for (res, proj), v in by_res.items())
            items.append(f"Frame time (median): {text}.")
        cluster = self.csv("cluster_bench.csv")
        if cluster:
            barrier = [r for r in cluster if r["part"] == "barrier"]
            if barrier:
                text = ", ".join(f"{r['nodes']} node{'s' if r['nodes'] != '1' else ''}: "
                                 f"{g(num(r['overhead_ms']), 2)} ms" for r in barrier)
                items.append(f"Cluster overhead per frame on one machine (local nodes): {text}.")
        self.add(*[f"- {i}" for i in items] or ["*No results.*"])
        self.add("", f"All on {self.machine_line()}.", "")

    def recommendation(self):
        rows = self.csv("lut_accuracy.csv")
        if not rows:
            return None
        group = [r for r in rows if r["preset"] == "all"] or rows
        pick = next((r for r in group if r.get("recommended") == "1"), None)
        default = next((r for r in group if r.get("project_default") == "1"), None)
        if not pick:
            return None
        text = (f"Recommended lookup-table setting (the cheapest precompute within "
                f"{g(num(pick['tolerance']), 2)}× of the best RMS error vs the reference solver): "
                f"**{pick['setting']}**, RMS {g(num(pick['rms_relative_error']))}, precompute "
                f"{f1(num(pick['precompute_s']))} s, frame {f1(num(pick['frame_ms']))} ms")
        if default and default is not pick:
            text += (f"; the project default ({default['setting']}): RMS "
                     f"{g(num(default['rms_relative_error']))}, precompute {f1(num(default['precompute_s']))} s, "
                     f"frame {f1(num(default['frame_ms']))} ms")
        elif default:
            text += " — the project default itself"
        else:
            text += "; the project default (paper sizes, 4 orders, GPU) was not measured in this run"
        return text + "."

    def accuracy(self):
        self.add("## Accuracy", "", "### Sky luminance against the CIE standard general sky (type 12)", "")
        self.add("The relative luminance L/Lz of the Earth presets seen from the ground (1.5 m), for view zenith "
                 "angles 0–85° along five azimuths from the sun, against CIE type 12 (\"standard clear sky, low "
                 "luminance turbidity\", the paper's Figure 10), for the presets as they are and with one of the "
                 "paper's extensions switched back (classic Rayleigh phase instead of Penndorf's, geometric instead "
                 "of Pickering's air mass). Directions within 5° of the sun are left out. Method: "
                 "[validation.md](validation.md).", "")
        summary, cases = self.validation("cie", "cie_summary.csv", "cie_cases.csv", "CIE")
        if not summary:
            return
        self.add("**Per model variant**, over all sun zenith angles and azimuths: RMS and largest |ΔL/Lz|, where "
                 "the largest is, the RMS at least 30° from the sun, and the best-fitting of the 15 CIE types.", "")
        self.add(table(["preset", "variant", "points", "RMS", "max", "max at (sun, azimuth, view zenith)",
                        "RMS ≥ 30° from sun", "best type (RMS)"],
                       [[r["preset"], r["variant"], r["points"], g(num(r["rms_type12"])), g(num(r["max_abs_type12"])),
                         f"{r['max_at_sun_zenith_deg']}°, {r['max_at_azimuth_deg']}°, {r['max_at_view_zenith_deg']}°",
                         g(num(r["rms_type12_far"])), f"{r['best_type']} ({g(num(r['best_type_rms']))})"]
                        for r in summary]), "")
        pooled = {}
        suns = []
        for r in cases:
            key = (r["preset"], r["variant"])
            sun = num(r["sun_zenith_deg"])
            if sun not in suns:
                suns.append(sun)
            p = pooled.setdefault(key, {}).setdefault(sun, [0.0, 0, 0.0])
            n = int(num(r["points"]) or 0)
            p[0] += n * (num(r["rms_type12"]) or 0.0) ** 2
            p[1] += n
            p[2] = max(p[2], num(r["max_abs_type12"]) or 0.0)
        self.add("**Per sun zenith angle** (all five azimuths): RMS / largest |ΔL/Lz| against type 12.", "")
        keys = list(pooled)
        rows = []
        for sun in suns:
            row = [f"{g(sun)}°"]
            for k in keys:
                s2, n, mx = pooled[k].get(sun, [0.0, 0, 0.0])
                row.append(f"{g(math.sqrt(s2 / n)) if n else '–'} / {g(mx)}")
            rows.append(row)
        self.add(table(["sun zenith"] + [f"{p} {v}" for p, v in keys], rows), "")
        self.add("L/Lz in the three vertical planes through the zenith (solar meridian, 45°/225°, 90°/270°), "
                 "ours against type 12:", "")
        for sun in suns:
            stem = f"cie_sun_zenith_{sun:02.0f}"
            self.image(os.path.join("cie", stem + ".png"), stem + ".png", f"L/Lz, sun zenith {g(sun)} deg")

        self.add("### Lookup tables against the reference solver", "")
        rows = self.csv("lut_accuracy.csv")
        if not rows:
            self.add("*lut_accuracy.csv missing.*", "")
            return
        self.add("Sky radiance from the tables against the independent reference solver (path tracing, "
                 "`tests/data/reference_*.csv`: noon, low sun, twilight and the limb from orbit; 400 000 paths per "
                 "wavelength and direction), relative error after discounting twice the reference's standard error. "
                 "The figures of every setting are in [Run time against error](#run-time-against-error); here the "
                 "project default and the recommended setting per atmosphere:", "")
        sel = [r for r in rows if r["preset"] != "all" and (r["project_default"] == "1" or r["recommended"] == "1")]
        self.add(table(["atmosphere", "setting", "RMS", "max", "why listed"],
                       [[r["preset"], r["setting"], g(num(r["rms_relative_error"])), g(num(r["max_relative_error"])),
                         ", ".join(x for x, c in (("project default", "project_default"),
                                                  ("recommended for this atmosphere", "recommended")) if r[c] == "1")]
                        for r in sel]) if sel else "*Neither measured.*", "")

    def measured_skies(self):
        self.add("### Sky radiance against measured skies (Kider et al. 2014)", "")
        self.add("The spectral sky radiance of the 15 public captures measured at Cornell on 2013-05-27 (81 "
                 "directions, 31 wavelengths 360–712.5 nm), against zenith on the atmosphere Bruneton 2017 inverted "
                 "for that day (nothing fitted to the captures), lit by the ASTM G173 sun; Bruneton's metric: per "
                 "capture the RMSE over directions and wavelengths, over the day the RMS of the captures'. The "
                 "published models' scores are his evaluation code's on the same captures. Method: "
                 "[validation.md](validation.md#measured-skies).", "")
        summary, captures = self.validation("measured", "measured_summary.csv", "measured_captures.csv",
                                            "measured-sky")
        if not summary:
            return
        r = summary[0]
        peers = [("Bruneton 2017 (40 wavelengths, 4 orders)", 11.34), ("Nishita 1996", 18.1),
                 ("Nishita 1993", 26.49), ("Hosek–Wilkie 2012 (turbidity 2.53)", 41.59), ("O'Neal 2005", 49.75),
                 ("Preetham 1999 (turbidity 2.53)", 88.72)]
        rows = [[f"**zenith ({r['tables']} tables, {r['wavelengths']} wavelengths)**",
                 f"**{num(r['spectral_rmse_mW_m2_sr_nm']):.2f}**"]]
        aeronet = self.csv("measured_aeronet", "measured_summary.csv")
        if aeronet:
            a = aeronet[0]
            rows.insert(0, [f"**zenith, the aerosol AERONET measured that day and ozone ({a['tables']} tables)**",
                            f"**{num(a['spectral_rmse_mW_m2_sr_nm']):.2f}**"])
            if a.get("days_sun_spectral_rmse_mW_m2_sr_nm"):
                rows.insert(0, [f"**the same under the Sun of that day ({num(a['sun_distance_au']):.5f} au, "
                                f"not the evaluation's 1 au)**",
                                f"**{num(a['days_sun_spectral_rmse_mW_m2_sr_nm']):.2f}**"])
        rows += [[m, f"{v:.2f}"] for m, v in peers]
        self.add(table(["model", "total RMSE (mW m⁻² sr⁻¹ nm⁻¹)"], rows), "")
        if aeronet:
            self.add("The AERONET rows: validate/data/cornell_2013-05-27_aeronet_ozone.json — the same atmosphere "
                     "with the aerosol phase function and optical depth AERONET retrieved that day at Egbert and the "
                     "U.S. Standard Atmosphere's ozone, nothing fitted to the captures; the first lit by the Sun at "
                     "its distance that day (ASTM G173 is at 1 au; the ephemeris), as zenith lights a dated sky, the "
                     "second by the evaluation's sun like the peers ([validation.md](validation.md#measured-skies)).",
                     "")
            self.provenance("measured_aeronet")
        self.add(f"Luminance RMSE {f1(num(r['luminance_rmse_cd_m2']))} cd m⁻², linear-sRGB chromaticity RMSE "
                 f"{g(num(r['chromaticity_rmse']))}. With the sun as the spectroradiometer sees it (ASTM G173 "
                 f"through a 3 nm slit at each measured wavelength instead of the evaluation's 11.75 nm bins, a change "
                 f"of input that would help every model, at the day's distance): "
                 f"{num(r['instrument_sun_spectral_rmse_mW_m2_sr_nm']):.2f}.",
                 "")
        if r.get("reference_samples"):
            self.add(f"The tables against the reference solver at {r['reference_directions']} directions of capture "
                     f"{r['reference_capture']} ({r['reference_samples']} paths per wavelength): RMSE "
                     f"{g(num(r['tables_vs_reference_mW_m2_sr_nm']))} mW m⁻² sr⁻¹ nm⁻¹ "
                     f"({g(num(r['tables_vs_reference_percent']))} % of the mean radiance; the path tracer's standard "
                     f"error {g(num(r['reference_standard_error_mW_m2_sr_nm']))}); against the measurements at these "
                     f"directions the tables score {g(num(r['tables_vs_measured_mW_m2_sr_nm']))} and the reference "
                     f"{g(num(r['reference_vs_measured_mW_m2_sr_nm']))}.", "")
        self.add(table(["capture (EDT)", "sun zenith", "RMSE (mW m⁻² sr⁻¹ nm⁻¹)", "luminance RMSE (cd m⁻²)",
                        "model / measured"],
                       [[c["time"], f"{f1(num(c['sun_zenith_deg']))}°", g(num(c["spectral_rmse_mW_m2_sr_nm"])),
                         f1(num(c["luminance_rmse_cd_m2"])), g(num(c["model_over_measured"]))] for c in captures]), "")
        self.image(os.path.join("measured", "measured_captures.png"), "measured_captures.png",
                   "spectral RMSE per capture")
        self.image(os.path.join("measured", "measured_spectral_ratio.png"), "measured_spectral_ratio.png",
                   "model over measured per wavelength")
        self.image(os.path.join("measured", "measured_rings.png"), "measured_rings.png",
                   "luminance along each ring of directions")

    def eclipse(self):
        self.add("### The sky of a total solar eclipse (reference solver and tables)", "")
        self.add("The zenith at NASA's point of greatest eclipse of 2017-08-21 from first to fourth contact, with "
                 "and without the Moon in front of the limb-darkened disc: the path tracer's, and the paper tables' "
                 "with the Moon's shadow (astro/eclipsed_sky.h, the sum the renderer draws), against measured "
                 "totality skies. Method: [validation.md](validation.md#eclipses).", "")
        self.provenance("eclipse")
        rows = self.csv("eclipse", "eclipse_zenith.csv")
        if not rows:
            self.add("*eclipse_zenith.csv missing.*", "")
            return
        self.add(table(["moment", "s from C2", "kind", "obscuration", "zenith / daylight 680 nm: reference",
                        "tables", "550 nm: reference", "tables", "440 nm: reference", "tables"],
                       [[r["moment"], r["seconds_from_second_contact"], r["kind"], g(num(r["obscuration"]))] +
                        [g(num(r.get(k % nm))) for nm in (680, 550, 440)
                         for k in ("zenith_ratio_%dnm", "tables_zenith_ratio_%dnm")] for r in rows]), "")
        self.image(os.path.join("eclipse", "eclipse_zenith.png"), "eclipse_zenith.png",
                   "the zenith through the 2017 eclipse")
        self.image(os.path.join("eclipse", "eclipse_totality.png"), "eclipse_totality.png",
                   "second to third contact")
        self.add("### The Moon in the Earth's shadow", "")
        self.add("The Moon's V magnitude below the uneclipsed Moon through the total lunar eclipse of 2019-01-21 "
                 "(astro/lunar_eclipse.h: sunlight refracted and extinguished through the model's air), against V "
                 "photometry; the drops at mid-totality of 2003, 2004 and 2022 are in the checks of the same run. "
                 "Method: [validation.md](validation.md#lunar-eclipses).", "")
        lunar = self.csv("eclipse", "lunar_eclipse_2019.csv")
        measured = [r for r in (lunar or []) if r.get("measured_v_minus_minimum_mag")]
        if measured:
            self.add(table(["UTC", "minutes from mid-eclipse", "Moon from the axis [km]", "measured V − minimum"],
                           [[r["utc"], r["minutes_from_mid"], r["axis_distance_km"],
                             r["measured_v_minus_minimum_mag"]] for r in measured]), "")
        self.image(os.path.join("eclipse", "lunar_eclipse_2019.png"), "lunar_eclipse_2019.png",
                   "the Moon through the 2019 lunar eclipse")

    def stability(self):
        self.add("## Numerical stability", "")
        self.add("`zenith validate stress` drives the hard corners — cameras from 1 m to 40 au, views on and within "
                 "1e-6 rad of the horizon, the sun through twilight and night, every preset and random parameter "
                 "sets — through the CPU table queries and rendered GPU frames, counting every NaN, ±Inf, negative "
                 "value and transmittance above 1, the largest relative jump across the horizon (±ε), and the "
                 "single-scattering error against the exact quadrature per region (relative, with a floor of "
                 "1e-6 sr⁻¹ per unit solar irradiance). Method: [validation.md](validation.md).", "")
        regions = self.measured("stress", "stress", "stress_regions.csv")
        if not regions:
            self.add("*stress_regions.csv missing.*", "")
            return
        cols = ["region", "configurations", "values", "NaN", "Inf", "negative", "T > 1", "largest horizon jump",
                "ref. median", "ref. p95", "ref. max"]

        def row(r, first):
            return [first, count(r["samples"]), count(r["values"]), r["nan"], r["inf"], r["negative"],
                    r["transmittance_above_1"], g(num(r["max_horizon_jump"])), g(num(r["reference_median"])),
                    g(num(r["reference_p95"])), g(num(r["reference_max"]))]

        self.add("**All models, per region:**", "")
        self.add(table(cols, [row(r, f"**{r['region']}**" if r["region"] == "all" else r["region"])
                              for r in regions if r["model"] == "all"]), "")
        self.add("**Per model, all regions:**", "")
        self.add(table(["model"] + cols[1:], [row(r, r["model"]) for r in regions
                                              if r["region"] == "all" and r["model"] != "all"]), "")
        gpu = self.csv("stress", "stress_gpu.csv")
        if gpu:
            by_model = {}
            for r in gpu:
                m = by_model.setdefault(r["model"], [0, 0, 0, 0, 0, 0.0, 0.0])
                m[0] += 1
                for i, k in enumerate(("values", "nan", "inf", "negative"), start=1):
                    m[i] += int(num(r[k]) or 0)
                m[5] = max(m[5], num(r["max_row_jump"]) or 0.0)
                m[6] = max(m[6], num(r["max_cpu_difference"]) or 0.0)
            self.add("**GPU path** (rendered frames: horizon strips and wide views per altitude and sun; the row jump "
                     "is the largest relative step between consecutive rows of a horizon frame inside the atmosphere, "
                     "the difference is against the CPU query of the same ray):", "")
            self.add(table(["model", "frames", "values", "NaN", "Inf", "negative", "largest row jump",
                            "largest GPU–CPU difference"],
                           [[k, v[0], count(v[1]), v[2], v[3], v[4], g(v[5]), g(v[6])] for k, v in by_model.items()]),
                     "")

    def pareto(self):
        self.add("## Run time against error", "")
        self.add("Every setting of the lookup tables — table sizes, scattering orders, quadrature along rays "
                 "(log-linear or trapezoid) and its samples, nodes of the scattering-density sphere integral, CPU "
                 "or GPU precompute — with its cost (the precompute time; the median frame time of a fisheye dome "
                 "master of a ground scene with those tables) against its error (RMS relative error of sky radiance "
                 "against the reference solver, over Earth and Mars together: mean cost, RMS pooled over every "
                 "direction and wavelength). A setting is on the **Pareto front** when no other has both a lower "
                 "cost and a lower error. **Rule for the recommended default:** the cheapest setting (precompute "
                 "time) whose RMS error is within the tolerance of the best; it is always on the front. Code: "
                 "`bench/lut_accuracy_bench.cpp`.", "")
        rows = self.measured("pareto", "lut_accuracy.csv")
        if not rows:
            self.add("*lut_accuracy.csv missing.*", "")
            return
        sizes = dict((r["sizes"], r["table_sizes"]) for r in rows)
        self.add("Table sizes: " + ", ".join(f"{k} `{v}`" for k, v in sizes.items()) +
                 " (transmittance μ×r, irradiance μs×r, scattering r×μ×μs×ν). Unless the name says otherwise: "
                 f"log-linear quadrature with 50 samples along rays, {default_sphere_nodes(rows)} sphere nodes.", "")
        presets = []
        for r in rows:
            if r["preset"] != "all" and r["preset"] not in presets:
                presets.append(r["preset"])
        by = {(r["setting"], r["preset"]): r for r in rows}
        group = [r for r in rows if r["preset"] == "all"] or [r for r in rows if r["preset"] == presets[0]]
        group.sort(key=lambda r: num(r["precompute_s"]) or 0.0)
        frame_size = next((r["frame_size_px"] for r in rows if r.get("frame_size_px") not in (None, "", "0")), None)
        self.add(f"Costs are means over {', '.join(presets)}; frame: {frame_size}×{frame_size} fisheye 180°. "
                 "Front: P = on the precompute-time front, F = on the frame-time front; ★ recommended; "
                 "D = the project default.", "")
        hdr = ["setting", "precompute s", "frame ms", "RMS", "max", "tables MB"] + \
              [f"RMS {p}" for p in presets] + ["front"]
        out = []
        for r in group:
            marks = "".join(m for m, c in (("P", "pareto_precompute"), ("F", "pareto_frame")) if r[c] == "1")
            if r["recommended"] == "1":
                marks += " ★"
            if r["project_default"] == "1":
                marks += " D"
            name = f"**{r['setting']}**" if r["recommended"] == "1" else r["setting"]
            out.append([name, f1(num(r["precompute_s"])), f1(num(r["frame_ms"])), g(num(r["rms_relative_error"])),
                        g(num(r["max_relative_error"])), g(num(r["table_MB"]))] +
                       [g(num(by.get((r["setting"], p), {}).get("rms_relative_error"))) for p in presets] + [marks])
        self.add(table(hdr, out), "")
        self.image("pareto_precompute.png", "pareto_precompute.png", "Precompute time against RMS error, Pareto front")
        self.image("pareto_frame.png", "pareto_frame.png", "Frame time against RMS error, Pareto front")
        text = self.recommendation()
        if text:
            self.add(f"**{text.split(':')[0]}:**{text.split(':', 1)[1]}", "")
        self.add("The frame time depends little on the tables (the passes take the same samples whatever the "
                 "table size; only the memory traffic differs), so on a shared machine the frame-time front mostly "
                 "reflects measurement noise; the precompute time is the cost that separates the settings. CPU and "
                 "GPU precomputes give the same tables (the same errors) at different times, so the frame-time "
                 "front counts the GPU settings only.", "")

    def speed(self):
        self.add("## Speed", "", "### Frame time (the paper's Table 2 layout)", "")
        self.add("The three-worlds scene (Earth, Mars, Titan, each with its atmosphere) in 16:9 planar views (90°) "
                 "and square fisheye dome masters (180°); the columns keep the first N atmospheres, \"bodies only\" "
                 "draws no atmosphere. Wall time around `Renderer::render()`, readback included; the median of the "
                 "frames, the fastest in brackets. Method: [rendering-performance.md](rendering-performance.md).", "")
        render = self.measured("render", "render_frame_times.csv")
        if render:
            order, cells, maxatm = [], {}, 0
            for r in render:
                key = (r["resolution"], r["projection"])
                if key not in order:
                    order.append(key)
                a = int(r["atmospheres"])
                maxatm = max(maxatm, a)
                cells[(key, a)] = f"{f1(num(r['frame_ms']))} ({f1(num(r['frame_ms_min']))})"
            self.add("**Frame time [ms], median (fastest)**", "")
            self.add(table(["resolution", "bodies only"] + [f"{n} ATM" for n in range(1, maxatm + 1)],
                           [[f"{res.replace('x', '×')} {proj.replace('deg', '°')}"] +
                            [cells.get((key, n), "–") for n in range(0, maxatm + 1)]
                            for key in order for res, proj in [key]]), "")
            self.add(f"Data: {self.data_path('render_frame_times.csv')}.", "")
            self.image("render_frame_times.png", "render_frame_times.png", "Frame time against atmospheres")
        else:
            self.add("*render_frame_times.csv missing.*", "")
        proj = self.csv("projector_frame_times.csv")
        if proj and "render" in self.steps and "viewport" in self.steps["render"]["command"]:
            self.add(f"**Per projector** of `{proj[0]['viewports']}` (all three atmospheres):", "")
            self.add(table(["output", "size", "median ms", "fastest ms", "peak memory MB"],
                           [[r["output"], r["size"], f1(num(r["frame_ms"])), f1(num(r["frame_ms_min"])),
                             r["peak_memory_mb"]] for r in proj]), "")

        self.add("### Precompute time per table size, CPU and GPU", "")
        rows = self.measured("pareto", "lut_accuracy.csv")
        sphere = default_sphere_nodes(rows or [])
        self.add(f"From the run-time-against-error measurement above (4 orders, log-linear, 50 ray samples, {sphere} "
                 "sphere nodes; GPU: a fresh headless EGL context per precompute, shader compilation included; CPU: "
                 "every core).", "")
        if rows:
            presets = [p for p in dict.fromkeys(r["preset"] for r in rows) if p != "all"]
            plain = [r for r in rows if r["orders"] == "4" and r["quadrature"] == "log-linear"
                     and r["ray_samples"] == "50" and r["sphere_samples"] == sphere and r["preset"] != "all"]
            sizes = list(dict.fromkeys(r["sizes"] for r in plain))
            t = {(r["sizes"], r["preset"], r["backend"]): r for r in plain}
            out = []
            for s in sizes:
                any_row = next(r for r in plain if r["sizes"] == s)
                out.append([s, f"`{any_row['table_sizes']}`", g(num(any_row["table_MB"]))] +
                           [f1(num(t[(s, p, b)]["precompute_s"])) if (s, p, b) in t else "–"
                            for p in presets for b in ("CPU", "GPU")])
            self.add(table(["sizes", "", "MB"] + [f"{p} {b} [s]" for p in presets for b in ("CPU", "GPU")], out), "")
            self.add("The GPU precompute here runs on the CPU too (llvmpipe's JIT-compiled shaders on the same cores); "
                     "on a real GPU it takes seconds." if "llvmpipe" in self.gl else "", "")

        self.add("### Cluster overhead per frame, 1–8 nodes", "")
        self.add("A real cluster on one machine: a `zenith master` and N `zenith node` processes on 127.0.0.1, each "
                 "node rendering a tiny output, frame pacing off. Overhead per frame = the mean frame period minus "
                 "the slowest node's render time (messages, decoding, scheduling, presenting); in-barrier = the "
                 "master's FrameState-out to last-RenderDone-in minus the slowest render. The nodes share the two "
                 "cores, so the period grows with N here; across machines the overhead is what a cluster adds. "
                 "Method: [cluster-performance.md](cluster-performance.md).", "")
        cluster = self.measured("cluster", "cluster_bench.csv")
        if cluster:
            self.add(table(["nodes", "frames", "fps", "period ms", "slowest render ms", "overhead ms",
                            "barrier ms", "in-barrier ms", "in-barrier p90 ms"],
                           [[r["nodes"], r["frames"], f1(num(r["fps"])), g(num(r["period_ms"])),
                             g(num(r["slowest_render_ms"])), g(num(r["overhead_ms"])), g(num(r["barrier_ms"])),
                             g(num(r["in_barrier_ms"])), g(num(r["in_barrier_p90_ms"]))]
                            for r in cluster if r["part"] == "barrier"]), "")
            bc = [r for r in cluster if r["part"] == "broadcast"]
            if bc:
                self.add("**Table broadcast** (master to every node on an empty cache: announce to the last node "
                         "ready; transfer = bytes on the wire, SHA-256 check, cache write):", "")
                self.add(table(["tables", "nodes", "MB", "broadcast s", "transfer s", "MB/s"],
                               [[r["tables"], r["nodes"], g((num(r["table_bytes"]) or 0) / 1e6), g(num(r["broadcast_s"])),
                                 g(num(r["transfer_s"])), g(num(r["mb_per_s"]))] for r in bc]), "")
            self.add(f"Data: {self.data_path('cluster_bench.csv')}.", "")

    def startup(self):
        self.add("### A show's start, Mesa's shader cache warm and empty", "")
        self.add("The process `zenith show render` up to its first frame (the three-worlds dome; tables from the "
                 "cache), median per case: **warm** as a second run leaves the caches, **cold-mesa** with the "
                 "driver's shader cache empty and zenith's program binaries kept, **cold-programs** with both "
                 "empty (a new machine or driver: every program compiled again), **cold-maps** with the albedo "
                 "maps not cached either. Then each pass's first use "
                 "(first frame less second, on llvmpipe its programs' code generation). "
                 "Method: [shows.md](shows.md#where-the-start-goes).", "")
        runs = self.measured("startup", "startup_times.csv")
        if runs:
            cases = list(dict.fromkeys(r["case"] for r in runs))
            columns = [k for k in runs[0] if k.endswith("_s") and k != "wall_s"]

            def median(values):
                values = sorted(v for v in values if v is not None)
                if not values:
                    return None
                n = len(values)
                return values[n // 2] if n % 2 else 0.5 * (values[n // 2 - 1] + values[n // 2])

            rows = [["whole process (wall)"] + [f"{median(num(r['wall_s']) for r in runs if r['case'] == c):.2f}"
                                                 for c in cases]]
            for k in columns:
                rows.append([k[:-2]] + [f"{median(num(r[k]) for r in runs if r['case'] == c):.2f}" for c in cases])
            self.add(table(["seconds"] + cases, rows), "")
            passes = self.csv("startup_pass_compile.csv")
            if passes:
                top = sorted(passes, key=lambda r: -(num(r["cold_first_use_ms"]) or 0))
                total_cold = sum(num(r["cold_first_use_ms"]) or 0 for r in passes)
                total_warm = sum(num(r["warm_first_use_ms"]) or 0 for r in passes)
                self.add(table(["pass", "first use, cache empty [ms]", "first use, cache warm [ms]"],
                               [[r["pass"], f1(num(r["cold_first_use_ms"])), f1(num(r["warm_first_use_ms"]))]
                                for r in top if (num(r["cold_first_use_ms"]) or 0) >= 1.0]
                               + [["**all passes**", f1(total_cold), f1(total_warm)]]), "")
            self.add(f"Data: {self.data_path('startup_times.csv')}, {self.data_path('startup_pass_compile.csv')}.",
                     "")

    def durations(self):
        self.add("## This run", "")
        self.add(table(["step", "command", "seconds", "exit code"],
                       [[k, f"`{s['command']}`", s["seconds"], s["rc"]] for k, s in self.steps.items()]), "")

    def write(self):
        self.header()
        self.headline()
        self.accuracy()
        self.measured_skies()
        self.eclipse()
        self.stability()
        self.pareto()
        self.speed()
        self.startup()
        self.durations()
        text = "\n".join(self.lines).rstrip() + "\n"
        with open(self.out, "w", encoding="utf-8") as f:
            f.write(text)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--machine", help="describe this machine into this JSON file and exit")
    p.add_argument("--data", help="folder with the CSV files of scripts/results")
    p.add_argument("--out", default="docs/RESULTS.md")
    p.add_argument("--images", default="docs/images/results")
    p.add_argument("--quick", action="store_true", help="mark the page as a quick run")
    a = p.parse_args()
    if a.machine:
        with open(a.machine, "w", encoding="utf-8") as f:
            json.dump(describe_machine(), f, indent=2)
            f.write("\n")
        return 0
    if not a.data:
        p.error("--data or --machine is required")
    if os.path.isdir(a.images):
        for name in os.listdir(a.images):
            if name.endswith(".png"):
                os.remove(os.path.join(a.images, name))
    Report(a.data, a.out, a.images, a.quick).write()
    print(f"results_report: wrote {a.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
