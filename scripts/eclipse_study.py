"""What the eclipse studies (scripts/eclipse-colour, scripts/eclipse-zenith-shift) share.

Standard library only; each function runs the `zenith` binary it is given.

* Where a total eclipse is: `total_eclipse_maximum` asks `zenith show plan`
  whether a place sees totality on a day, and when its maximum is there;
  `central_line` finds, at one longitude, the latitude midway between the
  path's edges (where the plan stops finding totality).
* What the model says: `sample_zenith` runs `zenith sample` for the zenith
  alone (the direction file `zenith.csv` in the run's folder).
* What the far field is made of: `ground_albedo` gives a real ground's
  spectral albedo (land covers and the sea from the CERES/SARB table, a lab
  sample of dry grass) at the study's wavelengths, as an atmosphere's
  `planet.ground_albedo` takes it.
* What an instrument would have measured: `implied_temperatures` multiplies a
  measured day sky (a Planck curve) by the model's eclipse ratio R(λ), the
  zenith with the Moon over the zenith without it, and fits each product with
  `zenith colour` — the same fit `zenith sample --colour` gives the model's
  own sky (image/colour.h).
"""
import csv
import io
import json
import math
import re
import subprocess

C2_NM_K = 1.438776877e7  # second radiation constant hc/k [nm K]


# The spectral albedo of landscapes by land cover, from the NASA CERES/SARB Surface Properties Project's table of
# the IGBP classes, as libRadtran 2.0.2 carries it (libsrc_f/IGBP_spectral_albedo.f, SPECALBIGBP; its bands in
# data/albedo/IGBP_map/wvl_albedo.dat): one albedo a band, for a sun 60° from the zenith, with no season. The
# bands [nm] that cover the studies' 380-755 nm, and the classes of a coastal plain and its sea.
CERES_BANDS_NM = ((357.5, 437.5), (437.5, 497.5), (497.5, 595.0), (595.0, 689.66), (689.66, 1298.7))
CERES_ALBEDO = {
    "evergreen-needleleaf-forest": (0.032, 0.032, 0.046, 0.046, 0.235),  # IGBP class 1
    "mixed-forest": (0.033, 0.033, 0.056, 0.057, 0.274),  # class 5
    "cropland-mosaic": (0.036, 0.045, 0.090, 0.083, 0.377),  # class 14, cropland and natural vegetation
    "water": (0.094, 0.091, 0.078, 0.072, 0.066),  # class 17
}
# A lab sample, not a landscape: dry grass (a piece of sod) in the ASTER spectral library 2.0 (Baldridge et al.
# 2009, Remote Sens. Environ. 113, 711), measured at Johns Hopkins University
# (jhu.becknic.vegetation.grass.dry.solid.drygras: lit from above, seen 60° off), linearly interpolated at these
# wavelengths [nm] (380 is its first sample's, 380.5 nm). Seen from a far field's distance, a landscape of it
# would be darker (its shadows): the brightest a ground rising toward the red could be.
DRY_GRASS_SAMPLE_NM = (380, 400, 425, 450, 475, 500, 525, 550, 575, 600, 625, 650, 675, 700, 725, 750, 775, 800)
DRY_GRASS_SAMPLE = (0.142, 0.157, 0.180, 0.205, 0.229, 0.251, 0.276, 0.306, 0.329, 0.353, 0.378, 0.403, 0.432,
                    0.461, 0.491, 0.508, 0.523, 0.537)

# 1970's far field made of real grounds: the land covers of the coastal plain under the path (each red edge read
# both ways, ground_albedo), the sea off it, and the lab sample as the brightest a ground rising to the red could be.
COASTAL_PLAIN_GROUNDS = ("evergreen-needleleaf-forest-step", "evergreen-needleleaf-forest-ramp", "mixed-forest-step",
                         "mixed-forest-ramp", "cropland-mosaic-step", "cropland-mosaic-ramp", "water-step",
                         "dry-grass-sample")
# The measurers' fit ran to 800 nm, the studies' wavelengths to 755: the grounds carried there.
BAND_CHECK_GROUNDS = (0.1, "cropland-mosaic-step", "cropland-mosaic-ramp", "mixed-forest-step", "dry-grass-sample")


def ground_label(ground):
    """A ground's name in the presets' file names and the CSVs: "albedo-0.1" for a grey one, its own otherwise."""
    return f"albedo-{ground}" if isinstance(ground, (int, float)) else ground


def interpolate(xs, ys, x):
    """ys at x, linear between the nodes xs (ascending) and constant beyond them."""
    if x <= xs[0]:
        return ys[0]
    for k in range(len(xs) - 1):
        if x <= xs[k + 1]:
            return ys[k] + (ys[k + 1] - ys[k]) * (x - xs[k]) / (xs[k + 1] - xs[k])
    return ys[-1]


def ground_albedo(ground, wavelengths_nm):
    """A ground's albedo as an atmosphere's `planet.ground_albedo` takes it: a number is a grey ground's; a land
    cover of CERES_ALBEDO as "<cover>-step", each band's albedo across the band (as libRadtran applies the table),
    or "<cover>-ramp", the same below 690 nm and linear above it from the red band's albedo to the near infrared's
    at its middle (994 nm) — one albedo from 690 to 1 300 nm cannot say where in it vegetation's red edge lies
    (700-750 nm), and the two bracket it: the step puts it at 690 nm, the ramp spreads it to 994;
    "dry-grass-sample" for DRY_GRASS_SAMPLE. A dict {"nm": albedo} at wavelengths_nm otherwise."""
    if isinstance(ground, (int, float)):
        return ground
    if ground == "dry-grass-sample":
        at = lambda w: interpolate(DRY_GRASS_SAMPLE_NM, DRY_GRASS_SAMPLE, w)
    else:
        cover, reading = ground.rsplit("-", 1)
        albedo = CERES_ALBEDO[cover]
        step = lambda w: next(a for (lo, hi), a in zip(CERES_BANDS_NM, albedo) if lo <= w < hi)
        (red_end, nir_end), nir_middle = CERES_BANDS_NM[-1], sum(CERES_BANDS_NM[-1]) / 2
        if reading == "step":
            at = step
        elif reading == "ramp":
            at = lambda w: step(w) if w < red_end else interpolate((red_end, nir_middle), albedo[-2:], w)
        else:
            raise ValueError(f"ground {ground!r}: a land cover's reading is -step or -ramp")
    return {f"{w}": round(at(w), 4) for w in wavelengths_nm}


def planck(wavelength_nm, temperature_K):
    """Planck's spectral radiance up to a constant factor: λ⁻⁵ / (exp(c₂ / λT) − 1)."""
    return wavelength_nm ** -5 / math.expm1(C2_NM_K / (wavelength_nm * temperature_K))


def read_spectrum(path):
    """The first row of a `zenith sample` CSV: its wavelengths [nm], relative radiances and the row itself."""
    row = next(csv.DictReader(open(path)))
    wavelengths = [int(k[len("L_rel_"):-len("nm_per_sr")]) for k in row if k.startswith("L_rel_")]
    return wavelengths, [float(row[f"L_rel_{w}nm_per_sr"]) for w in wavelengths], row


def method_arguments(method):
    """`zenith sample`'s arguments for a method as the studies' CSVs name it: lut (the tables), reference (the
    path tracer) or reference-polarized (the path tracer's vector radiative transfer)."""
    return ["--method", "reference", "--polarized"] if method == "reference-polarized" else ["--method", method]


def sample_zenith(zenith, out, atmosphere, method, samples, name, args):
    """`zenith sample` of the zenith of this atmosphere (a preset's name or a JSON path) by `method`
    (method_arguments), with `args` added: read_spectrum's answer for the CSV it writes (out/name.csv), and the
    run's log."""
    path = f"{out}/{name}.csv"
    run = subprocess.run([zenith, "sample", "--atmosphere", atmosphere, "--directions", f"{out}/zenith.csv",
                          "--samples", str(samples), "--out", path] + method_arguments(method) + args,
                         capture_output=True, text=True, check=True)
    return read_spectrum(path), run.stderr


def kelvin(cell):
    """A temperature as `zenith colour` and `zenith sample --colour` write it, in whole kelvins, or inf."""
    return cell if cell == "inf" else f"{float(cell):.0f}"


def implied_temperatures(zenith, path, wavelengths, ratios, day_temperature_K, band_nm):
    """For each R(λ) in ratios, the effective blackbody temperature over band_nm (first, last) of a day sky that
    is a day_temperature_K Planck curve times R — what its observer would have measured at totality if the model
    were the sky. The spectra go to path (one column each) for `zenith colour`."""
    with open(path, "w") as f:
        f.write("wavelength_nm," + ",".join(f"case{k}" for k in range(len(ratios))) + "\n")
        for i, w in enumerate(wavelengths):
            f.write(f"{w}," + ",".join(f"{planck(w, day_temperature_K) * 1e15 * r[i]:.9g}" for r in ratios) + "\n")
    fitted = subprocess.run([zenith, "colour", "--spectrum", path, "--band-nm", f"{band_nm[0]},{band_nm[1]}"],
                            check=True, capture_output=True, text=True).stdout
    by_column = {r["column"]: r["T_eff_K"] for r in csv.DictReader(io.StringIO(fitted))}
    return [kelvin(by_column[f"case{k}"]) for k in range(len(ratios))]


def total_eclipse_maximum(zenith, out, date, latitude_deg, longitude_deg):
    """The moment of maximum (ISO 8601, UTC) of a total solar eclipse seen from this sea-level place on this day,
    from `zenith show plan`; None where the eclipse there is partial or there is none. Writes a scene and a show
    into the folder out."""
    scene = json.load(open("configs/scenes/earth-eclipse-2027-luxor.json"))
    scene["time"] = f"{date}T00:00:00Z"
    scene["site"] = {"latitude_deg": latitude_deg, "longitude_deg": longitude_deg, "altitude_m": 0}
    scene["camera"]["surface"].update({"latitude_deg": latitude_deg, "longitude_deg": longitude_deg})
    json.dump(scene, open(f"{out}/scene.json", "w"))
    show = {"zenith_show": 1, "name": "eclipse-study", "scene": "scene.json", "fps": 1, "loop": False,
            "time": {"start": f"{date}T00:00:00Z", "time_rate": 3600, "end_s": 24}}
    json.dump(show, open(f"{out}/show.json", "w"))
    plan = subprocess.run([zenith, "show", "plan", "--show", f"{out}/show.json"], capture_output=True, text=True,
                          check=True).stdout
    m = re.search(r"holds a total solar eclipse, maximum (\S+) (\S+) UTC", plan)
    return f"{m.group(1)}T{m.group(2)}Z" if m else None


def central_line(zenith, out, date, latitude0_deg, longitude_deg):
    """The latitude midway between the path's edges at this longitude (each found by bisection to 0.002°, walking
    out from latitude0_deg, which must be inside the path, in 0.5° steps) and the moment of maximum there. The
    path must cross the meridian steeply here, or its edges are its ends, not its sides."""
    def maximum(latitude):
        return total_eclipse_maximum(zenith, out, date, latitude, longitude_deg)

    if maximum(latitude0_deg) is None:
        raise SystemExit(f"no total eclipse on {date} at {latitude0_deg}°, {longitude_deg}°: "
                         "give a latitude inside the path")

    def edge(step):
        inside, outside = latitude0_deg, latitude0_deg + step
        while maximum(outside) is not None:
            inside, outside = outside, outside + step
        while abs(outside - inside) > 0.002:
            middle = 0.5 * (inside + outside)
            if maximum(middle) is None:
                outside = middle
            else:
                inside = middle
        return inside

    latitude = round(0.5 * (edge(0.5) + edge(-0.5)), 3)
    return latitude, maximum(latitude)
