"""Writes the synthetic luminaire files of this folder (run from here: python3 make_synthetic.py).

Every intensity follows a closed form that the tests evaluate themselves (tests/lighting/):
  I(C, gamma) [cd/klm] = (200 + 40 g(C)) (1 + gamma / 90)
with g(C) = cos C (symmetric about the C0-C180 plane), sin C (about the C90-C270 plane), cos 2C (both
planes), 0 (rotational), and cos C + 0.5 sin C (no symmetry). C every 45 deg, gamma 0-180 by 45 deg."""
import math

GAMMA = [0.0, 45.0, 90.0, 135.0, 180.0]
C_ALL = [45.0 * k for k in range(8)]
G = {
    "none": lambda c: math.cos(math.radians(c)) + 0.5 * math.sin(math.radians(c)),
    "rotational": lambda c: 0.0,
    "c0-c180": lambda c: math.cos(math.radians(c)),
    "c90-c270": lambda c: math.sin(math.radians(c)),
    "quadrants": lambda c: math.cos(math.radians(2 * c)),
}


def intensity(symmetry, c, gamma):
    return (200.0 + 40.0 * G[symmetry](c)) * (1.0 + gamma / 90.0)


def fmt(x):
    return f"{x:.6f}".rstrip("0").rstrip(".")


def ldt(isym, symmetry, planes, name, lamp_number="1", flux=2000.0, lorl=80.0, conversion="1"):
    lines = ["Synthetic Lighting Co.", "1", str(isym), str(len(C_ALL)), "45", str(len(GAMMA)), "45", "R-1", name,
             "N-1", name + ".ldt", "2026-12-06", "600", "200", "100", "500", "150", "20", "30", "20", "30", "95",
             fmt(lorl), conversion, "0", "1", lamp_number, "LED", fmt(flux), "4000K", "80", "25"]
    lines += ["0.5"] * 10
    lines += [fmt(c) for c in C_ALL] + [fmt(g) for g in GAMMA]
    for c in planes:
        lines += [fmt(intensity(symmetry, c, g)) for g in GAMMA]
    return "\r\n".join(lines) + "\r\n"


files = {
    "isym0.ldt": ldt(0, "none", C_ALL, "isym0"),
    "isym1.ldt": ldt(1, "rotational", [0.0], "isym1"),
    "isym2.ldt": ldt(2, "c0-c180", [0.0, 45.0, 90.0, 135.0, 180.0], "isym2"),
    # The planes C270 ... C315, C0 ... C90, in that order.
    "isym3.ldt": ldt(3, "c90-c270", [270.0, 315.0, 0.0, 45.0, 90.0], "isym3"),
    "isym4.ldt": ldt(4, "quadrants", [0.0, 45.0, 90.0], "isym4"),
    # Absolute photometry: a negative number of lamps; the flux is the luminaire's.
    "absolute.ldt": ldt(4, "quadrants", [0.0, 45.0, 90.0], "absolute", lamp_number="-1", flux=1500.0, lorl=100.0),
}


def ies_values(symmetry, horizontal, per_line=3):
    out = []
    for c in horizontal:
        row = [fmt(intensity(symmetry, c, g)) for g in GAMMA]
        out += [" ".join(row[k:k + per_line]) for k in range(0, len(row), per_line)]
    return out


# LM-63-2002, quadrant symmetry (0-90), angle lists over several lines and comma delimiters,
# multiplier 2 and ballast factor 0.9, relative photometry: 2 lamps of 1000 lm.
files["quadrants_2002.ies"] = "\n".join(
    ["IESNA:LM-63-2002", "[TEST] synthetic 1", "[TESTLAB] none", "[ISSUEDATE] 2026-12-06",
     "[MANUFAC] Synthetic Lighting Co.", "[LUMINAIRE] quadrant test luminaire", "[MORE] second line of the name",
     "TILT=NONE", "2 1000 2 5 3 1 2 0.5 0.6 0.1", "0.9 1 30", "0, 45, 90,", "135 180", "0 45", "90"]
    + ies_values("quadrants", [0.0, 45.0, 90.0])) + "\n"
# LM-63-1995 with TILT=INCLUDE, C0-C180 symmetry, feet.
files["tilt_1995.ies"] = "\n".join(
    ["IESNA:LM-63-1995", "[MANUFAC] Synthetic Lighting Co.", "[LUMCAT] TILT-1", "TILT=INCLUDE", "1", "3",
     "0 45 90", "1 0.95 0.9", "1 2000 1 5 5 1 1 1.5 2 0", "1 1 40", " ".join(fmt(g) for g in GAMMA),
     "0 45 90 135 180"] + ies_values("c0-c180", [0.0, 45.0, 90.0, 135.0, 180.0], per_line=5)) + "\n"
# LM-63-2019, no symmetry (0-360 with the 360 plane repeating 0), absolute photometry.
files["full_2019.ies"] = "\n".join(
    ["IES:LM-63-2019", "[TEST] synthetic 3", "[TESTLAB] none", "[ISSUEDATE] 2026-12-06",
     "[MANUFAC] Synthetic Lighting Co.", "[LUMINAIRE] full circle", "TILT=NONE", "1 -1 1 5 9 1 2 0.3 0.3 0",
     "1 1 20", " ".join(fmt(g) for g in GAMMA), " ".join(fmt(c) for c in C_ALL + [360.0])]
    + ies_values("none", C_ALL + [0.0], per_line=5)) + "\n"
# IESNA91: one horizontal angle (rotational symmetry), ballast-lamp photometric factor 0.95 applied.
files["rotational_1991.ies"] = "\n".join(
    ["IESNA91", "[LUMINAIRE] round", "TILT=NONE", "1 1000 1 5 1 1 2 -0.4 -0.4 0.05", "1 0.95 10",
     " ".join(fmt(g) for g in GAMMA), "0"] + ies_values("rotational", [0.0], per_line=5)) + "\n"
# The 1986 format (no format line), symmetric about the C90-C270 plane (horizontal angles 90-270).
files["c90_c270_1986.ies"] = "\n".join(
    ["[MANUFAC] Synthetic Lighting Co.", "free text line of the 1986 format", "TILT=NONE",
     "1 1000 1 5 5 1 2 0 0 0", "1 1 10", " ".join(fmt(g) for g in GAMMA), "90 135 180 225 270"]
    + ies_values("c90-c270", [90.0, 135.0, 180.0, 225.0, 270.0], per_line=5)) + "\n"

for name, text in files.items():
    with open(name, "w", newline="") as f:
        f.write(text)
