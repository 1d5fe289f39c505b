#!/usr/bin/env python3
"""Write roadbrdf's own synthetic instrument files, from the format descriptions in docs/data.md
("Instrument files") -- no real file is copied or read.

    python3 tests/data/instruments/make_synthetic.py OUTPUT_FOLDER [CORPUS_FOLDER]

The files are not kept in the repository: CMake runs this script when it configures the tests
(tests/CMakeLists.txt), into BUILD/tests/data/instruments, and the fuzz seeds of the asd, sed, sig
and manifest parsers into BUILD/tests/fuzz/corpus/<parser>/ (CORPUS_FOLDER); the pytest fixture
`instruments` runs it into a scratch folder.

Every signal is a closed form, so that the tests know the expected values without reading the
files back with the code under test:

  wavelengths  350 + k nm, k = 0..CHANNELS-1 (ASD, SED); the SIG file has its own grid (below)
  white W(l)   = 20000 + 4 l             (DN; the white-reference panel as target)
  dark  D      = 100                     (DN)
  sample k     = D + F_k (W(l) - D) (1 + l / 10000)   with F_k = 0.1, 0.2, 0.3 for samples 1..3
  stored reference of every ASD/SED sample file = W(l)

so that (S - D)/(W - D) = F_k (1 + l/10000) exactly (up to rounding of the text files). The panel
reflectance file rho.txt is rho(l) = 0.95 + 0.00001 (l - 350).
"""
import os
import re
import struct
import sys

CHANNELS = 21          # 350..370 nm keeps the files small
FIRST, STEP = 350.0, 1.0
DARK = 100.0
FACTORS = [0.1, 0.2, 0.3]


def wavelengths():
    return [FIRST + STEP * k for k in range(CHANNELS)]


def white(l):
    return 20000.0 + 4.0 * l


def sample(k, l):
    return DARK + FACTORS[k] * (white(l) - DARK) * (1.0 + l / 10000.0)


# ---- ASD binary ------------------------------------------------------------------------------
# Header fields and offsets as docs/data.md lists them (little-endian).
def asd_header(version, data_type, data_format, it_ms=68, gains=(118, 616), offsets=(2076, 2253),
               dark_corrected=1, saturation=0):
    h = bytearray(484)
    h[0:3] = version.encode()
    comment = b"roadbrdf synthetic file"
    h[3:3 + len(comment)] = comment
    struct.pack_into("<9h", h, 160, 30, 15, 10, 24, 4, 124, 0, 0, 0)  # 2024-05-24 10:15:30
    h[178] = 0x60  # program version 6.0
    h[179] = {"as6": 0x60, "as7": 0x70, "as8": 0x80}[version]
    h[181] = dark_corrected
    h[186] = data_type
    struct.pack_into("<ff", h, 191, FIRST, STEP)
    h[199] = data_format
    struct.pack_into("<H", h, 204, CHANNELS)
    struct.pack_into("<I", h, 390, it_ms)
    struct.pack_into("<H", h, 400, 12345)          # instrument number
    h[422] = saturation
    struct.pack_into("<3H", h, 425, 10, 10, 25)    # dark, reference, sample counts
    h[431] = 4                                     # FieldSpec full range
    struct.pack_into("<4H", h, 436, gains[0], gains[1], offsets[0], offsets[1])
    struct.pack_into("<ff", h, 444, 1000.0, 1830.0)
    return bytes(h)


def values(v, data_format):
    code = {0: "f", 1: "i", 2: "d"}[data_format]
    if data_format == 1:
        v = [int(round(x)) for x in v]
    return struct.pack("<%d%s" % (len(v), code), *v)


def bstr(text):
    b = text.encode()
    return struct.pack("<h", len(b)) + b


def asd_file(version, data_type, data_format, target, reference, reference_flag=True, calibrations=(),
             audit=b"", **header):
    out = bytearray(asd_header(version, data_type, data_format, **header))
    out += values(target, data_format)
    out += struct.pack("<H", 0xFFFF if reference_flag else 0)
    out += struct.pack("<dd", 45436.25, 45436.26)  # OLE dates: 2024-05-24 06:00 and 06:14:24
    out += bstr("synthetic white reference")
    out += values(reference, data_format)
    # classifier data: 2 bytes, 20 empty strings, constituent count 0 and its 2 bytes
    out += b"\x00\x00" + b"\x00\x00" * 20 + b"\x00\x00" + b"\x00\x00"
    if version in ("as7", "as8"):
        out += b"\x00\x00" + b"\x00\x00" + b"\x00" * 4  # no dependent variables
        out += struct.pack("<B", len(calibrations))
        for ctype, name, it, g1, g2, _ in calibrations:
            out += struct.pack("<B20sIHH", ctype, name.encode(), it, g1, g2)
        for *_, spectrum in calibrations:
            out += struct.pack("<%dd" % CHANNELS, *spectrum)
    out += audit
    return bytes(out)


# ---- text files ------------------------------------------------------------------------------
def sed_file(target, reference, reflectance=True, units="DN"):
    rad = units != "DN"
    lines = ["Comment: roadbrdf synthetic file", "Version: 2.2", "Instrument: PSR+3500_SN0000000 [3]",
             "Detectors: 512,256,256", "Measurement: REFLECTANCE" if reflectance else "Measurement: DIRECT_ENERGY",
             "Date: 05/24/2024,05/24/2024", "Time: 10:00:00,10:05:00", "Averages: 10,10",
             "Integration: 50,50,30,50,50,30", "Dark Mode: AUTO,AUTO",
             "Radiometric Calibration: " + ("RADIANCE" if rad else "DN"),
             "Units: " + ("W/m^2/sr/nm" if rad else "None"), "Wavelength Range: 350,370",
             "Channels: %d" % CHANNELS, "Columns [%d]:" % (4 if reflectance else 3), "Data:"]
    name = "Rad." if rad else "Norm. DN"
    lines.append("\t".join(["Wvl", name + " (Ref.)", name + " (Target)"] + (["Reflect. %"] if reflectance else [])))
    for l, t, r in zip(wavelengths(), target, reference):
        row = ["%.1f" % l, "%.9E" % r, "%.9E" % t] + (["%.6f" % (100.0 * t / r)] if reflectance else [])
        lines.append("\t".join(row))
    return ("\r\n".join(lines) + "\r\n").encode()


# SIG: two detectors, 340..380 nm every 2 nm, then 370..400 nm every 2 nm (overlap 370..380 nm).
SIG_LOWER = [340.0 + 2 * k for k in range(21)]   # 340..380
SIG_UPPER = [370.0 + 2 * k for k in range(16)]   # 370..400


def sig_file(overlap=True):
    lines = ["/*** Spectra Vista SIG Data ***/", "name= synthetic.sig", "instrument= HI: 0000000 (HR-1024i)",
             "integration= 100.0, 10.0, 10.0, 100.0, 10.0, 10.0", "units= Radiance, Radiance",
             "time= 5/24/2024 10:00:00 AM, 5/24/2024 10:01:00 AM",
             "factors= 1.000, 1.000, 1.000 [Overlap: Preserve, Matching Type: None]", "data= "]
    grid = [(l, 0) for l in SIG_LOWER] + [(l, 1) for l in SIG_UPPER] if overlap else [(l, 0) for l in SIG_LOWER]
    for l, detector in grid:
        ref = 1000.0 + l + 1000.0 * detector    # the detectors differ: the tests can tell which was kept
        tgt = 0.25 * ref
        lines.append("%.1f  %.2f  %.2f  %.2f" % (l, ref, tgt, 25.0))
    return ("\r\n".join(lines) + "\r\n").encode()


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit("usage: make_synthetic.py OUTPUT_FOLDER [CORPUS_FOLDER]")
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    wl = wavelengths()
    W = [white(l) for l in wl]
    files = {}
    ident = lambda: [1.0] * CHANNELS
    # ASD: the white, the dark and three samples of a run (v8, doubles), raw data type.
    files["run_white.asd"] = asd_file("as8", 0, 2, W, W, audit=b"<Audit_Event>synthetic</Audit_Event>",
                                      dark_corrected=0)
    files["run_dark.asd"] = asd_file("as8", 0, 2, [DARK] * CHANNELS, W, dark_corrected=0)
    for k in range(3):
        files["run_%03d.asd" % (k + 1)] = asd_file("as8", 0, 2, [sample(k, l) for l in wl], W, dark_corrected=0)
    # Versions and formats: v6 float reflectance, v7 radiance with calibration blocks, v7 integer.
    files["v6_float_reflectance.asd"] = asd_file("as6", 1, 0, [sample(0, l) for l in wl], W)
    files["v7_radiance_calibrations.asd"] = asd_file(
        "as7", 2, 2, [sample(1, l) for l in wl], W, reference_flag=False,
        calibrations=[(1, "bse00000.ref", 0, 0, 0, [0.99] * CHANNELS), (2, "lmp00000.ill", 0, 0, 0, ident()),
                      (3, "fo00000.raw", 136, 31, 16, W)])
    files["v7_integer_saturated.asd"] = asd_file("as7", 0, 1, [sample(2, l) for l in wl], W, saturation=0x01)
    files["white_it34.asd"] = asd_file("as8", 0, 2, W, W, it_ms=34)  # other settings than the run
    # SED: a run with the white reference stored in each sample file, and a file without reflectance.
    for k in range(3):
        files["sed_%03d.sed" % (k + 1)] = sed_file([sample(k, l) - DARK for l in wl], [w - DARK for w in W])
    files["sed_no_reflectance.sed"] = sed_file([sample(0, l) for l in wl], W, reflectance=False)
    files["sig_overlap.sig"] = sig_file(True)
    files["sig_no_overlap.sig"] = sig_file(False)
    # Panel reflectance and manifests.
    files["rho.txt"] = ("# synthetic panel reflectance\nwavelength,rho\n" + "".join(
        "%g,%.6f\n" % (l, 0.95 + 0.00001 * (l - 350.0)) for l in range(340, 401))).encode()
    files["run.csv"] = (b"# sample: synthetic ASD run\nfile,role,gamma,alpha,beta,delta\n"
                        b"run_white.asd,white,,,,\nrun_dark.asd,dark,,,,\n"
                        b"run_001.asd,sample,0,45,0,0\nrun_002.asd,sample,30,45,0,0\nrun_003.asd,sample,60,45,0,0\n")
    files["run_sed.csv"] = (b"file,role,theta_i,phi_i,theta_r,phi_r\n"
                            b"sed_001.sed,sample,0,0,30,180\nsed_002.sed,sample,20,0,30,180\n"
                            b"sed_003.sed,sample,40,0,30,180\n")
    files["run_settings_mismatch.csv"] = (b"file,role,gamma,alpha,beta,delta\nwhite_it34.asd,white,,,,\n"
                                          b"run_001.asd,sample,0,45,0,0\n")
    for name, data in files.items():
        write(os.path.join(out, name), data)
    if len(sys.argv) == 3:
        # Fuzz seeds: one file of each reader's variants.
        seeds = {"asd": ["run_001.asd", "v6_float_reflectance.asd", "v7_integer_saturated.asd",
                         "v7_radiance_calibrations.asd"],
                 "sed": ["sed_001.sed", "sed_no_reflectance.sed"],
                 "sig": ["sig_overlap.sig", "sig_no_overlap.sig"],
                 "manifest": ["run.csv", "run_sed.csv"]}
        # Regression inputs of crashes once found, made from our own synthetic files (never from a real one): a
        # channel count beyond every integer (an out-of-range float-to-integer cast) and a line holding only
        # carriage returns (an empty row reached cells.back()).
        sed = files["sed_001.sed"].decode()
        seeds_made = {("sed", "regression-channel-count-beyond-integers.sed"):
                      re.sub(r"Channels: *[0-9]+", "Channels: 1e30", sed, count=1).encode(),
                      ("sig", "regression-carriage-return-only-line.sig"): files["sig_no_overlap.sig"] + b"\r\r\n"}
        for parser, names in seeds.items():
            os.makedirs(os.path.join(sys.argv[2], parser), exist_ok=True)
            for name in names:
                write(os.path.join(sys.argv[2], parser, name), files[name])
        for (parser, name), data in seeds_made.items():
            write(os.path.join(sys.argv[2], parser, name), data)


def write(path, data):
    """Writes only when the content changed, so that a re-configure does not touch the files."""
    if os.path.exists(path):
        with open(path, "rb") as f:
            if f.read() == data:
                return
    with open(path + ".part", "wb") as f:
        f.write(data)
    os.replace(path + ".part", path)


if __name__ == "__main__":
    main()
