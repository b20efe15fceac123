"""Read refractiveindex.info material files (YAML) with the standard library.

The database files (github: polyanskiy/refractiveindex.info-database, CC0)
use a small, regular subset of YAML: top-level keys, literal blocks
("REFERENCES: |"), and a DATA list whose items hold "type", "data" (a block
of numbers), "wavelength_range" and "coefficients". This module parses only
that subset, so the demo generator needs no PyYAML.

Supported DATA types (as the database documents them, wavelength in µm):
  tabulated nk / tabulated n / tabulated k   rows of wavelength, n[, k]
  formula 1  Sellmeier      n²-1 = C1 + Σ Ci λ²/(λ² - C(i+1)²)
  formula 2  Sellmeier-2    n²-1 = C1 + Σ Ci λ²/(λ² - C(i+1))
  formula 3  polynomial     n²   = C1 + Σ Ci λ^C(i+1)
  formula 4  RefractiveIndex.INFO
             n² = C1 + C2 λ^C3/(λ² - C4^C5) + C6 λ^C7/(λ² - C8^C9) + Σ_{i>=10} Ci λ^C(i+1)
  formula 5  Cauchy         n    = C1 + Σ Ci λ^C(i+1)
Tabulated data are interpolated linearly in wavelength and held constant
beyond their ends (the engine's convention for spectra); formulas are
evaluated as written, also outside their stated range (a dispersion formula
is a physical model; the caller is told when that happens).
"""

import bisect
import html
import math
import re
from pathlib import Path


def _parse_yaml_subset(text):
    """Parse the refractiveindex.info YAML subset into dicts, lists and strings."""
    lines = [line.rstrip("\n") for line in text.splitlines()]
    doc = {}
    i = 0

    def indent_of(line):
        return len(line) - len(line.lstrip(" "))

    def read_block(start, min_indent):
        """Lines of a literal block scalar, dedented; returns (text, next index)."""
        body = []
        j = start
        while j < len(lines) and (not lines[j].strip() or indent_of(lines[j]) >= min_indent):
            body.append(lines[j])
            j += 1
        while body and not body[-1].strip():
            body.pop()
        nonblank = [indent_of(b) for b in body if b.strip()]
        cut = min(nonblank) if nonblank else 0
        return "\n".join(b[cut:] for b in body), j

    def scalar(value):
        value = value.strip()
        if len(value) >= 2 and value[0] == value[-1] and value[0] in "'\"":
            value = value[1:-1]
        return value

    while i < len(lines):
        line = lines[i]
        if not line.strip() or line.lstrip().startswith("#"):
            i += 1
            continue
        if indent_of(line) != 0:
            raise ValueError(f"line {i + 1}: unexpected indentation: {line!r}")
        key, sep, rest = line.partition(":")
        if not sep:
            raise ValueError(f"line {i + 1}: expected 'KEY: value': {line!r}")
        key, rest = key.strip(), rest.strip()
        if rest in ("|", "|-", "|+", ">"):
            doc[key], i = read_block(i + 1, 1)
        elif rest:
            doc[key] = scalar(rest)
            i += 1
        else:
            # Nested content: a list of mappings ("- k: v") or a mapping.
            i += 1
            items = None
            mapping = {}
            current = None
            item_indent = None
            while i < len(lines) and (not lines[i].strip() or indent_of(lines[i]) > 0):
                sub = lines[i]
                if not sub.strip() or sub.lstrip().startswith("#"):
                    i += 1
                    continue
                stripped = sub.strip()
                if stripped.startswith("- "):
                    items = [] if items is None else items
                    current = {}
                    items.append(current)
                    item_indent = indent_of(sub) + 2
                    stripped = stripped[2:]
                    this_indent = item_indent
                else:
                    this_indent = indent_of(sub)
                target = current if current is not None else mapping
                k, s, v = stripped.partition(":")
                if not s:
                    raise ValueError(f"line {i + 1}: expected 'key: value': {sub!r}")
                k, v = k.strip(), v.strip()
                if v in ("|", "|-", "|+", ">"):
                    target[k], i = read_block(i + 1, this_indent + 1)
                else:
                    target[k] = scalar(v)
                    i += 1
            doc[key] = items if items is not None else mapping
    return doc


def _reference_text(raw):
    """REFERENCES field as one line of plain text, keeping DOIs and links."""
    def link(match):
        url, label = match.group(1), match.group(2)
        label = re.sub(r"<[^>]+>", "", label).strip()
        if "doi.org/" in url:
            return f"{label}, doi:{url.split('doi.org/', 1)[1]}"
        return f"{label}, {url}"

    text = re.sub(r'<a href="([^"]*)"\s*>(.*?)</a>', link, raw, flags=re.S)
    text = re.sub(r"<br\s*/?>", "; ", text)
    text = re.sub(r"<[^>]+>", "", text)
    text = html.unescape(text)
    text = re.sub(r"\s+", " ", text)
    return re.sub(r"\s+;", ";", text).strip().rstrip(";").strip()


class Table:
    """Linear interpolation on increasing abscissae, ends held constant."""

    def __init__(self, xs, ys):
        pairs = sorted(zip(xs, ys))
        self.xs = [p[0] for p in pairs]
        self.ys = [p[1] for p in pairs]

    def __call__(self, x):
        xs, ys = self.xs, self.ys
        if x <= xs[0]:
            return ys[0]
        if x >= xs[-1]:
            return ys[-1]
        j = bisect.bisect_right(xs, x)
        t = (x - xs[j - 1]) / (xs[j] - xs[j - 1])
        return ys[j - 1] + t * (ys[j] - ys[j - 1])


def _formula(kind, c, lam):
    """Refractive index n of the database's dispersion formula `kind` at lam µm."""
    c = list(c) + [0.0] * 20  # missing trailing coefficients are zero
    l2 = lam * lam
    if kind == 1:
        n2 = 1.0 + c[0]
        for i in range(1, 17, 2):
            if c[i]:
                n2 += c[i] * l2 / (l2 - c[i + 1] ** 2)
    elif kind == 2:
        n2 = 1.0 + c[0]
        for i in range(1, 17, 2):
            if c[i]:
                n2 += c[i] * l2 / (l2 - c[i + 1])
    elif kind == 3:
        n2 = c[0]
        for i in range(1, 17, 2):
            if c[i]:
                n2 += c[i] * lam ** c[i + 1]
    elif kind == 4:
        n2 = c[0]
        if c[1]:
            n2 += c[1] * lam ** c[2] / (l2 - c[3] ** c[4])
        if c[5]:
            n2 += c[5] * lam ** c[6] / (l2 - c[7] ** c[8])
        for i in range(9, 17, 2):
            if c[i]:
                n2 += c[i] * lam ** c[i + 1]
    elif kind == 5:
        n = c[0]
        for i in range(1, 17, 2):
            if c[i]:
                n += c[i] * lam ** c[i + 1]
        return n
    else:
        raise ValueError(f"formula {kind} is not implemented")
    return math.sqrt(n2)


class Material:
    """Complex refractive index n + ik of one database file, wavelength in nm."""

    def __init__(self, path):
        self.path = Path(path)
        doc = _parse_yaml_subset(self.path.read_text(encoding="utf-8"))
        self.reference = _reference_text(doc.get("REFERENCES", ""))
        self.database_path = self.path.name.replace("__", "/")
        self._n = None
        self._k = None
        self.kinds = []
        self.range_um = None  # where the n data are valid
        for item in doc.get("DATA", []):
            kind = item["type"].strip()
            self.kinds.append(kind)
            if kind.startswith("tabulated"):
                rows = [[float(v) for v in row.split()] for row in item["data"].splitlines() if row.strip()]
                lam = [r[0] for r in rows]
                columns = kind.split()[1]
                if "n" in columns:
                    self._n = Table(lam, [r[1] for r in rows])
                    self.range_um = (min(lam), max(lam))
                if "k" in columns:
                    self._k = Table(lam, [r[columns.index("k") + 1] for r in rows])
            elif kind.startswith("formula"):
                number = int(kind.split()[1])
                coeffs = [float(v) for v in item["coefficients"].split()]
                self._n = (lambda lam, number=number, coeffs=coeffs: _formula(number, coeffs, lam))
                lo, hi = (float(v) for v in item["wavelength_range"].split())
                self.range_um = (lo, hi)
            else:
                raise ValueError(f"{self.path.name}: unsupported DATA type '{kind}'")
        if self._n is None:
            raise ValueError(f"{self.path.name}: no refractive index data")

    def covers(self, wavelength_nm):
        lo, hi = self.range_um
        return lo <= wavelength_nm / 1000.0 <= hi

    def n(self, wavelength_nm):
        return self._n(wavelength_nm / 1000.0)

    def k(self, wavelength_nm):
        return self._k(wavelength_nm / 1000.0) if self._k is not None else 0.0

    def nk(self, wavelength_nm):
        return complex(self.n(wavelength_nm), self.k(wavelength_nm))

    def outside_range(self, wavelengths_nm):
        """Wavelengths (nm) where the data are extrapolated or held constant."""
        return [w for w in wavelengths_nm if not self.covers(w)]
