#!/usr/bin/env python3
"""mtlx_check.py FILE...: each MaterialX document written by `brdf --out x.mtlx`
is well-formed XML (parsed back with the standard library), a <materialx>
root of version 1.39 holding one open_pbr_surface and one surfacematerial
that uses it, every input a standard OpenPBR input (name and type as in
MaterialX's libraries/bxdf/open_pbr_surface.mtlx, OpenPBR 1.x) with a value
in the nodedef's range, and the ΔE00 per geometry in the material's doc."""
import re
import sys
import xml.etree.ElementTree as ET

# name: (type, lowest, highest) of the open_pbr_surface nodedef (ui ranges;
# the ior are physical: above 1).
STANDARD = {
    "base_weight": ("float", 0.0, 1.0),
    "base_color": ("color3", 0.0, 1.0),
    "base_diffuse_roughness": ("float", 0.0, 1.0),
    "base_metalness": ("float", 0.0, 1.0),
    "specular_weight": ("float", 0.0, 1.0),
    "specular_color": ("color3", 0.0, 1.0),
    "specular_roughness": ("float", 0.0, 1.0),
    "specular_ior": ("float", 1.0, 10.0),
    "specular_roughness_anisotropy": ("float", 0.0, 1.0),
    "coat_weight": ("float", 0.0, 1.0),
    "coat_color": ("color3", 0.0, 1.0),
    "coat_roughness": ("float", 0.0, 1.0),
    "coat_ior": ("float", 1.0, 3.0),
    "coat_darkening": ("float", 0.0, 1.0),
    "thin_film_weight": ("float", 0.0, 1.0),
    "thin_film_thickness": ("float", 0.0, 2.0),
    "thin_film_ior": ("float", 1.0, 3.0),
}
REQUIRED = {"base_color", "base_metalness", "specular_roughness", "specular_ior", "coat_weight"}


def check(path):
    errors = []
    root = ET.parse(path).getroot()  # raises on malformed XML
    if root.tag != "materialx" or root.get("version") != "1.39":
        errors.append(f"root <{root.tag} version={root.get('version')}>, not <materialx version=1.39>")
    surfaces = root.findall("open_pbr_surface")
    materials = root.findall("surfacematerial")
    if len(surfaces) != 1 or len(materials) != 1:
        return errors + [f"{len(surfaces)} open_pbr_surface and {len(materials)} surfacematerial, not one each"]
    surface, material = surfaces[0], materials[0]
    if surface.get("type") != "surfaceshader" or material.get("type") != "material":
        errors.append("node types are not surfaceshader and material")
    for name in (surface.get("name"), material.get("name")):
        if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", name or ""):
            errors.append(f"element name {name!r} is not a MaterialX name")
    uses = material.find("input[@name='surfaceshader']")
    if uses is None or uses.get("nodename") != surface.get("name"):
        errors.append("the surfacematerial does not use the open_pbr_surface")
    seen = set()
    for node in surface.findall("input"):
        name, kind, value = node.get("name"), node.get("type"), node.get("value")
        if name not in STANDARD:
            errors.append(f"input {name!r} is not an OpenPBR input")
            continue
        seen.add(name)
        want, lo, hi = STANDARD[name]
        if kind != want:
            errors.append(f"input {name}: type {kind}, the standard's is {want}")
        numbers = [float(v) for v in value.split(",")]
        if len(numbers) != (3 if want == "color3" else 1):
            errors.append(f"input {name}: {value!r} is not one {want}")
        for v in numbers:
            if not lo <= v <= hi:
                errors.append(f"input {name}: {v} outside [{lo}, {hi}]")
    missing = REQUIRED - seen
    if missing:
        errors.append(f"inputs missing: {sorted(missing)}")
    doc = material.get("doc") or ""
    if len(re.findall(r"45as-?\d+ \d+\.\d\d", doc)) != 6:
        errors.append(f"the material's doc does not give ΔE00 at six geometries: {doc!r}")
    return errors


def main():
    failed = 0
    for path in sys.argv[1:]:
        try:
            errors = check(path)
        except ET.ParseError as e:
            errors = [f"not well-formed XML: {e}"]
        print(f"{path}: {'ok' if not errors else 'FAIL'}")
        for e in errors:
            print(f"  {e}")
        failed += bool(errors)
    return 1 if failed or len(sys.argv) < 2 else 0


if __name__ == "__main__":
    sys.exit(main())
