#!/usr/bin/env python3
"""Writes the hand-made seed inputs of Refracta's fuzz targets (Testing/Fuzz/Corpus/<target>/).

The binary targets read their bytes with refracta_fuzz::FuzzBytes (FuzzSupport.h); the helpers
below encode values the same way, so each seed is a readable description of a hostile case.
Inputs that libFuzzer found (crashes fixed since, or new coverage) are added as files of their
own next to these and are never regenerated. Run from anywhere: python3 make_seeds.py
"""
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
EDGE = ["0", "-0", "1", "-1", "0.5", "2", "1e-300", "denorm", "-denorm", "dblmin", "1e-45",
        "1e-30", "1e30", "-1e30", "1e300", "-1e300", "DBL_MAX", "-DBL_MAX", "FLT_MAX",
        "-FLT_MAX", "3.5e38", "nan", "inf", "-inf", "1e9", "16384", "2^31", "0.9999",
        "1.0000001"]


def integer(k, lo, hi):
    """FuzzBytes::Int(lo, hi) reading k (spans of at most 256 values)."""
    assert lo <= k <= hi and hi - lo < 256
    return bytes([k - lo])


def lattice(v):
    """A FuzzBytes::Lattice value: v in [-8, 8), a multiple of 1/16."""
    b = int(round(v * 16)) + 128
    assert 0 <= b <= 255 and abs((b - 128) / 16.0 - v) < 1e-12, v
    return bytes([b])


def double(v):
    """FuzzBytes::Double: a lattice value where possible, an edge value by name, else raw bits."""
    if isinstance(v, str):
        return bytes([5, EDGE.index(v)])
    if v == int(v * 16) / 16.0 and -8 <= v < 8:
        return bytes([0]) + lattice(v)
    return bytes([6]) + struct.pack(">d", v)


def write(target, name, data):
    folder = os.path.join(HERE, target)
    os.makedirs(folder, exist_ok=True)
    mode = "w" if isinstance(data, str) else "wb"
    with open(os.path.join(folder, name), mode) as f:
        f.write(data)


# ---- FuzzMeshVoxelizer ------------------------------------------------------------------------
TETRA_POINTS = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
TETRA = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
CUBE_POINTS = [(x, y, z) for z in (-0.5, 0.5) for y in (-0.5, 0.5) for x in (-0.5, 0.5)]
CUBE = [(0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6), (0, 1, 5), (0, 5, 4), (2, 6, 7), (2, 7, 3),
        (0, 4, 6), (0, 6, 2), (1, 3, 7), (1, 7, 5)]


def mesh(points, cells, material=(4, 2, 2, 4)):
    """points: (x, y, z) values for double(); cells: tuples of ids (a triangle) or
    ("poly"|"strip"|"line"|"vert", ids...); material: index, extinction, albedo, g steps."""
    out = integer(len(points), 0, 40)
    for p in points:
        out += b"".join(double(c) for c in p)
    out += integer(len(cells), 0, 60)
    for c in cells:
        kinds = {"poly": 200, "strip": 201, "line": 202, "vert": 203}
        if isinstance(c[0], str):
            kind, ids = c[0], c[1:]
            out += bytes([kinds[kind]])
            if kind == "poly":
                out += integer(len(ids), 1, 6)
            elif kind == "strip":
                out += integer(len(ids), 3, 6)
        else:
            ids = c
            out += bytes([0])
        for i in ids:
            out += point_id(i, len(points))
    n, e, a, g = material
    return out + integer(n, 0, 8) + integer(e, 0, 4) + integer(a, 0, 4) + integer(g, -4, 4)


def point_id(i, n):
    if i == -1:
        return bytes([240])
    if i == n:
        return bytes([241])
    if i > n:
        return bytes([242, i - n])
    assert 0 <= i < n and i < 240
    return bytes([i])


def voxelizer(meshes, dims=(4, 4, 4), supersampling=2, window=3, check=True, bounds=None,
              padding=1):
    out = integer(len(meshes), 1, 2) + b"".join(integer(d, 1, 6) for d in dims)
    out += integer(supersampling, 1, 3) + integer(window, 1, 5) + bytes([0 if check else 255])
    if bounds:
        out += bytes([1]) + b"".join(double(b) for b in bounds)
    else:
        out += bytes([0])
    out += integer(padding, 0, 3)
    return out + b"".join(meshes)


def scaled(points, s, shift=(0, 0, 0)):
    return [tuple(c * s + d for c, d in zip(p, shift)) for p in points]


V = "FuzzMeshVoxelizer"
write(V, "tetrahedron", voxelizer([mesh(TETRA_POINTS, TETRA)]))
write(V, "cube", voxelizer([mesh(CUBE_POINTS, CUBE)], dims=(5, 5, 5), supersampling=3))
write(V, "cube_inside_out", voxelizer([mesh(CUBE_POINTS, [(a, c, b) for a, b, c in CUBE])]))
write(V, "cube_one_face_flipped",
      voxelizer([mesh(CUBE_POINTS, [(0, 3, 2)] + CUBE[1:])]))
write(V, "nested_cubes", voxelizer([mesh(CUBE_POINTS, CUBE),
                                    mesh(scaled(CUBE_POINTS, 0.5), CUBE, (8, 4, 4, -4))]))
write(V, "overlapping_cubes", voxelizer([mesh(CUBE_POINTS, CUBE),
                                         mesh(scaled(CUBE_POINTS, 1, (0.25, 0.25, 0)), CUBE)]))
write(V, "cube_quads", voxelizer([mesh(CUBE_POINTS, [
    ("poly", 0, 2, 3, 1), ("poly", 4, 5, 7, 6), ("poly", 0, 1, 5, 4), ("poly", 2, 6, 7, 3),
    ("poly", 0, 4, 6, 2), ("poly", 1, 3, 7, 5)])]))
write(V, "cube_strips_lines_verts", voxelizer([mesh(CUBE_POINTS, CUBE[2:] + [
    ("strip", 0, 2, 1, 3), ("line", 0, 7), ("vert", 5)])]))
write(V, "open_cube", voxelizer([mesh(CUBE_POINTS, CUBE[:-1])]))
write(V, "non_manifold_edge", voxelizer([mesh(CUBE_POINTS, CUBE + [(0, 3, 5)])]))
write(V, "two_tetras_sharing_a_vertex", voxelizer([mesh(
    TETRA_POINTS + [(-1, 0, 0), (0, -1, 0), (0, 0, -1)],
    TETRA + [(0, 4, 5), (0, 6, 4), (0, 5, 6), (4, 6, 5)])]))
write(V, "self_intersecting", voxelizer([mesh(
    TETRA_POINTS + scaled(TETRA_POINTS, 1, (0.25, 0.25, 0.25)),
    TETRA + [(a + 4, b + 4, c + 4) for a, b, c in TETRA])]))
write(V, "self_intersecting_unchecked", voxelizer([mesh(
    TETRA_POINTS + scaled(TETRA_POINTS, 1, (0.25, 0.25, 0.25)),
    TETRA + [(a + 4, b + 4, c + 4) for a, b, c in TETRA])], check=False))
write(V, "degenerate_collinear", voxelizer([mesh(
    TETRA_POINTS + [(0.5, 0, 0)], TETRA + [(0, 4, 1)])]))
write(V, "zero_area_repeated_vertex", voxelizer([mesh(TETRA_POINTS, TETRA + [(0, 0, 1)])]))
write(V, "duplicated_points", voxelizer([mesh(TETRA_POINTS + TETRA_POINTS,
                                              [(0, 6, 1), (4, 1, 7), (0, 3, 6), (5, 2, 3)])]))
write(V, "flat_zero_volume", voxelizer([mesh(
    [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)], [(0, 1, 2), (1, 3, 2), (0, 2, 1), (1, 2, 3)])]))
write(V, "nan_coordinate", voxelizer([mesh([("nan", 0, 0)] + TETRA_POINTS[1:], TETRA)]))
write(V, "inf_coordinate", voxelizer([mesh([(0, "-inf", 0)] + TETRA_POINTS[1:], TETRA)]))
write(V, "huge_coordinates", voxelizer([mesh(
    [("1e300", 0, 0), ("-1e300", 0, 0), (0, "1e300", 0), (0, 0, "1e300")], TETRA)]))
write(V, "dbl_max_coordinates", voxelizer([mesh(
    [("-DBL_MAX", "-DBL_MAX", "-DBL_MAX"), ("DBL_MAX", 0, 0), (0, "DBL_MAX", 0),
     (0, 0, "DBL_MAX")], TETRA)]))
write(V, "denormal_tetrahedron", voxelizer([mesh(
    [(0, 0, 0), ("denorm", 0, 0), (0, "denorm", 0), (0, 0, "denorm")], TETRA)]))
write(V, "index_minus_one", voxelizer([mesh(TETRA_POINTS, TETRA[:3] + [(1, 2, -1)])]))
write(V, "index_past_end", voxelizer([mesh(TETRA_POINTS, TETRA[:3] + [(1, 2, 4)])]))
write(V, "index_far_past_end", voxelizer([mesh(TETRA_POINTS, TETRA[:3] + [(1, 2, 200)])]))
write(V, "quad_with_bad_index", voxelizer([mesh(CUBE_POINTS, CUBE[2:] + [("poly", 0, 2, 9, 1)])]))
write(V, "no_points", voxelizer([mesh([], [])]))
write(V, "explicit_bounds_nan", voxelizer([mesh(TETRA_POINTS, TETRA)],
                                          bounds=(0, 1, 0, "nan", 0, 1)))
write(V, "explicit_bounds_huge", voxelizer([mesh(TETRA_POINTS, TETRA)],
                                           bounds=("-1e300", "1e300", 0, 1, 0, 1)))
write(V, "grid_through_vertices", voxelizer([mesh(scaled(CUBE_POINTS, 2), CUBE)], dims=(3, 3, 3),
                                            supersampling=1, window=1, padding=0))

# ---- FuzzMediumValidator ----------------------------------------------------------------------
NAMES = ["RefractiveIndex", "RefractiveIndexGradient", "Extinction", "Albedo", "Anisotropy",
         "Emission", "Occupancy", "Density"]
TYPES = {"double": 0, "int": 1, "uchar": 2, "short": 3, "idtype": 4, "string": 5, "float": 6}
COMPONENTS = {"RefractiveIndex": 1, "RefractiveIndexGradient": 3, "Extinction": 3, "Albedo": 3,
              "Anisotropy": 1, "Emission": 3, "Occupancy": 1, "Density": 1}


def validator_image(extent_counts=(2, 2, 2), spacing=(1, 1, 1), origin=(0, 0, 0),
                    direction=None, arrays=(), require=True, starts=(0, 0, 0)):
    out = b""
    for s, n in zip(starts, extent_counts):
        if s == "far":
            out += bytes([241]) + integer(n - 1, -1, 4)
        else:
            out += bytes([0]) + integer(s, -3, 3) + integer(n - 1, -1, 4)
    out += b"".join(double(v) for v in spacing) + b"".join(double(v) for v in origin)
    if direction is None:
        out += bytes([0])
    elif direction == "rotation":
        out += bytes([2]) + lattice(0.5)
    elif direction == "permutation":
        out += bytes([1, 3, 1, 0, 1])
    else:
        out += bytes([3]) + b"".join(double(v) for v in direction)
    out += bytes([0 if require else 255]) + integer(len(arrays), 0, 8)
    for a in arrays:
        out += array(**a)
    return out


def array(name, values, kind="float", cell=False, components=None, tuples_delta=0):
    out = integer(NAMES.index(name), 0, 7) + bytes([255 if cell else 0, TYPES[kind]])
    out += integer(components or COMPONENTS[name], 0, 4)
    out += bytes([225 + tuples_delta + 2]) if tuples_delta else bytes([0])
    for v in values:
        if kind in ("float", "double"):
            out += double(v)
        elif kind == "string":
            out += integer(v, 0, 3)
        else:
            out += integer(v + (0 if kind == "uchar" else 128), 0, 255)
    return out


def full_medium(n=8, **bad):
    arrays = []
    for name in NAMES[:-1]:
        c = COMPONENTS[name]
        value = {"RefractiveIndex": 1.5, "Albedo": 0.5, "Anisotropy": 0.25,
                 "Occupancy": 1}.get(name, 0.5)
        values = [bad.get(name, value)] + [value] * (n * c - 1)
        arrays.append(dict(name=name, values=values))
    return arrays


M = "FuzzMediumValidator"
write(M, "valid_medium", validator_image(arrays=full_medium()))
write(M, "valid_rotated", validator_image(direction="rotation", arrays=full_medium()))
write(M, "valid_permuted", validator_image(direction="permutation", arrays=full_medium()))
write(M, "nan_index", validator_image(arrays=full_medium(RefractiveIndex="nan")))
write(M, "index_below_one", validator_image(arrays=full_medium(RefractiveIndex=0.5)))
write(M, "negative_extinction", validator_image(arrays=full_medium(Extinction=-1)))
write(M, "inf_emission", validator_image(arrays=full_medium(Emission="inf")))
write(M, "albedo_above_one", validator_image(arrays=full_medium(Albedo=2)))
write(M, "anisotropy_one", validator_image(arrays=full_medium(Anisotropy=1)))
write(M, "denormal_extinction", validator_image(arrays=full_medium(Extinction="denorm")))
write(M, "huge_extinction", validator_image(arrays=full_medium(Extinction="1e30")))
write(M, "empty_axis", validator_image(extent_counts=(2, 0, 2), arrays=full_medium(0)))
write(M, "far_extent", validator_image(starts=("far", 0, 0), arrays=full_medium()))
write(M, "zero_spacing", validator_image(spacing=(1, 0, 1), arrays=full_medium()))
write(M, "negative_spacing", validator_image(spacing=(1, 1, -1), arrays=full_medium()))
write(M, "nan_spacing", validator_image(spacing=("nan", 1, 1), arrays=full_medium()))
write(M, "denormal_spacing", validator_image(spacing=("denorm", 1, 1), arrays=full_medium()))
write(M, "inf_origin", validator_image(origin=(0, "inf", 0), arrays=full_medium()))
write(M, "singular_direction", validator_image(direction=(1, 0, 0, 1, 0, 0, 0, 0, 1),
                                               arrays=full_medium()))
write(M, "sheared_direction", validator_image(direction=(1, 0.5, 0, 0, 1, 0, 0, 0, 1),
                                              arrays=full_medium()))
write(M, "nan_direction", validator_image(direction=(1, 0, 0, 0, "nan", 0, 0, 0, 1),
                                          arrays=full_medium()))
write(M, "no_arrays", validator_image())
write(M, "no_arrays_allowed", validator_image(require=False))
write(M, "cell_data_index", validator_image(arrays=[
    dict(name="RefractiveIndex", values=[1], cell=True)]))
write(M, "string_index", validator_image(arrays=[
    dict(name="RefractiveIndex", values=[1] * 8, kind="string")]))
write(M, "wrong_components", validator_image(arrays=[
    dict(name="Extinction", values=[0.5] * 16, components=2)]))
write(M, "too_few_tuples", validator_image(arrays=[
    dict(name="Occupancy", values=[0.5] * 6, tuples_delta=-2)]))
write(M, "too_many_tuples", validator_image(arrays=[
    dict(name="Occupancy", values=[0.5] * 10, tuples_delta=2)]))
write(M, "integer_arrays", validator_image(arrays=[
    dict(name="RefractiveIndex", values=[1] * 7 + [0], kind="int"),
    dict(name="Albedo", values=[1] * 24, kind="uchar"),
    dict(name="Occupancy", values=[-1] + [0] * 7, kind="short"),
    dict(name="Anisotropy", values=[0] * 8, kind="idtype")]))
write(M, "duplicate_arrays", validator_image(arrays=full_medium()[:4] + full_medium(
    RefractiveIndex="nan")[:1]))

# ---- FuzzTransferFunctionMedium ---------------------------------------------------------------
SCALAR_TYPES = {"double": 0, "int": 1, "uchar": 2, "float": 3}


def tf_input(dims=(2, 2, 2), kind="double", values=None, components=1, tuples_delta=0,
             opacity=((0, 0), (1, 0.5)), grey=None, colour=((0, 1, 1, 1),), unit=None,
             index=None, g=0, emission=0, no_property=False):
    out = b"".join(integer(d, 0, 5) for d in dims) + integer(0, 0, 3) * 3 + lattice(0) * 3
    out += bytes([SCALAR_TYPES[kind]])
    out += bytes([234 + components - 1]) if components != 1 else bytes([0])
    out += bytes([235 + tuples_delta + 2]) if tuples_delta else bytes([0])
    n = dims[0] * dims[1] * dims[2]
    values = values if values is not None else [i / 16.0 for i in range(n * components)]
    for v in values:
        out += double(v) if kind in ("double", "float") else bytes([v])
    out += bytes([255 if no_property else 0])
    if not no_property:
        out += function(opacity, 5)
        if grey is not None:
            out += bytes([1]) + function(grey, 4)
        else:
            out += bytes([0]) + integer(len(colour), 0, 4)
            for x, r, gg, b in colour:
                out += double(x) + double(r) + double(gg) + double(b)
        out += (bytes([1]) + double(unit)) if unit is not None else bytes([0])
    out += (bytes([1]) + function(index, 4)) if index is not None else bytes([0])
    return out + double(g) + double(emission)


def function(points, most):
    out = integer(len(points), 0, most)
    for x, y in points:
        out += double(x) + double(y)
    return out


T = "FuzzTransferFunctionMedium"
write(T, "simple", tf_input())
write(T, "grey_with_index", tf_input(grey=((0, 0.2), (1, 0.9)), index=((0, 1), (1, 1.5)),
                                     g=0.5, emission=1))
write(T, "opacity_one", tf_input(opacity=((0, 1), (1, 1))))
write(T, "unit_distance_zero", tf_input(unit=0))
write(T, "unit_distance_negative", tf_input(unit=-1))
write(T, "unit_distance_denormal", tf_input(unit="denorm", emission="1e30"))
write(T, "unit_distance_nan", tf_input(unit="nan"))
write(T, "opacity_nan", tf_input(opacity=((0, "nan"),)))
write(T, "colour_nan", tf_input(colour=((0, "nan", 0.5, 0.5),)))
write(T, "grey_inf", tf_input(grey=((0, "inf"),)))
write(T, "index_nan", tf_input(index=((0, "nan"),)))
write(T, "index_huge", tf_input(index=((0, "1e300"),)))
write(T, "anisotropy_nan", tf_input(g="nan"))
write(T, "emission_nan", tf_input(emission="nan"))
write(T, "emission_huge", tf_input(emission="1e30", unit=1e-30))
write(T, "scalars_nan", tf_input(values=["nan"] + [0] * 7))
write(T, "scalars_huge_float", tf_input(kind="float", values=["1e300"] + [0] * 7))
write(T, "scalars_uchar", tf_input(kind="uchar", values=list(range(0, 255, 32))))
write(T, "three_components", tf_input(components=3))
write(T, "too_few_tuples", tf_input(tuples_delta=-2, values=[0] * 6))
write(T, "too_many_tuples", tf_input(tuples_delta=2, values=[0] * 10))
write(T, "empty_image", tf_input(dims=(0, 2, 2), values=[]))
write(T, "no_property", tf_input(no_property=True))
write(T, "no_opacity_points", tf_input(opacity=()))

# ---- FuzzSceneFile (JSON) ---------------------------------------------------------------------
S = "FuzzSceneFile"
sphere = {"medium": {"grid": {"dimensions": [4, 4, 4], "bounds": [-1, 1, -1, 1, -1, 1]},
                     "meshes": [{"sphere": {"center": [0, 0, 0], "radius": 0.5},
                                 "material": {"refractive_index": 1.5}}]}}


def scene(name, base=None, **changes):
    s = json.loads(json.dumps(base if base is not None else sphere))
    s.update(changes)
    write(S, name + ".json", json.dumps(s, indent=1) + "\n")


scene("sphere")
scene("everything", image={"width": 32, "height": 16, "exposure": 2, "tone_mapping": "reinhard"},
      camera={"position": [0, 0, 3], "focal_point": [0, 0, 0], "view_up": [0, 1, 0],
              "view_angle": 40, "projection": "parallel", "parallel_scale": 1},
      background={"checker": {"squares": [4, 2], "color1": [1, 1, 1], "color2": [0, 0, 0]},
                  "up": [0, 1, 0], "right": [1, 0, 0]},
      lights=[{"type": "spot", "position": [0, 2, 0], "focal_point": [0, 0, 0], "cone_angle": 20,
               "exponent": 2, "color": [1, 1, 1], "intensity": 5},
              {"type": "directional", "position": [1, 1, 1]},
              {"type": "point", "position": [0, 0, 2]}],
      quality={"preset": "draft", "photons": 1024, "seed": 3, "view_step": 0.5,
               "ray_mode": "curved", "transmittance_cutoff": 0.01, "photon_min_step": 0.5,
               "octree_tolerance": 0.01, "photon_smoothing": False, "multiple_scattering": True,
               "multiple_scattering_tolerance": 0.001, "multiple_scattering_block_size": 2,
               "tolerance": 0.05},
      effects={"refraction": "on", "absorption": "off", "single_scattering": "auto",
               "multiple_scattering": "auto", "emission": "off"})
scene("box_and_file", medium={"grid": {"dimensions": [5, 5, 5], "padding": 0.1,
                                       "supersampling": 2, "smoothing_window": 3},
                              "surrounding": {"extinction": [0.1, 0.1, 0.1], "albedo": [1, 1, 1],
                                              "anisotropy": 0.5},
                              "meshes": [{"box": {"bounds": [-1, 1, -1, 1, -1, 1]}},
                                         {"file": "tetrahedron.ply",
                                          "material": {"emission": [1, 1, 1],
                                                       "extinction": [1, 1, 1]}}]})
scene("volume_medium", medium={"volume": {"file": "medium.vti"}})
scene("volume_transfer_function", medium={"volume": {
    "file": "scalars.vti", "array": "density",
    "transfer_function": {"opacity": [[0, 0], [1, 0.5]], "color": [[0, 1, 1, 1], [1, 1, 0, 0]],
                          "unit_distance": 0.5, "refractive_index": [[0, 1], [1, 1.3]],
                          "anisotropy": 0.3, "emission_scale": 1}}})
scene("volume_not_a_medium", medium={"volume": {"file": "scalars.vti"}})
scene("environment_image", background={"environment": "environment.png"})
scene("missing_file", medium={"meshes": [{"file": "no_such_mesh.ply"}]})
scene("unsupported_extension", medium={"meshes": [{"file": "medium.vti"}]})
scene("volume_file_is_a_mesh", medium={"volume": {"file": "tetrahedron.ply"}})
scene("open_mesh_file", medium={"meshes": [{"file": "open_triangle.ply"}]})
scene("unknown_key", image={"colour": 1})
scene("width_negative", image={"width": -5})
scene("width_huge", image={"width": 1e300})
scene("width_float", image={"width": 2.5})
scene("exposure_denormal", image={"exposure": 5e-324})
scene("exposure_1e30", image={"exposure": 1e30})
scene("grid_1e30_bounds", medium={"grid": {"dimensions": [3, 3, 3],
                                           "bounds": [-1e30, 1e30, -1, 1, -1, 1]},
                                  "meshes": [{"sphere": {"radius": 1e29}}]})
scene("grid_bounds_reversed", medium={"grid": {"bounds": [1, -1, -1, 1, -1, 1]},
                                      "meshes": [{"sphere": {}}]})
scene("sphere_tiny_radius", medium={"meshes": [{"sphere": {"radius": 1e-30}}]})
scene("sphere_outside_grid", medium={"grid": {"dimensions": [3, 3, 3],
                                              "bounds": [-1, 1, -1, 1, -1, 1]},
                                     "meshes": [{"sphere": {"center": [100, 0, 0]}}]})
scene("two_kinds_of_mesh", medium={"meshes": [{"sphere": {}, "box": {"bounds": [0, 1, 0, 1, 0, 1]}}]})
scene("no_medium", base={})
scene("meshes_and_volume", medium={"meshes": [], "volume": {}})
scene("light_focal_point_equal", lights=[{"type": "point", "position": [0, 0, 0]}])
scene("light_cone_not_spot", lights=[{"type": "point", "position": [1, 0, 0], "cone_angle": 10}])
scene("light_exactly_on_grid_corner", lights=[{"type": "point", "position": [-1, -1, -1],
                                               "focal_point": [1, 1, 1]}])
scene("camera_inside_medium", camera={"position": [0, 0, 0], "focal_point": [0, 0, -1]})
scene("camera_position_equals_focal", camera={"position": [1, 1, 1], "focal_point": [1, 1, 1]})
scene("camera_view_up_zero", camera={"view_up": [0, 0, 0]})
scene("camera_view_up_parallel", camera={"position": [0, 3, 0], "focal_point": [0, 0, 0],
                                         "view_up": [0, 1, 0]})
scene("preset_unknown", quality={"preset": "ultra"})
scene("checker_too_many_squares", background={"checker": {"squares": [100000, 2]}})
scene("background_two_kinds", background={"color": [0, 0, 0], "checker": {}})
scene("transfer_function_bad_opacity", medium={"volume": {
    "file": "scalars.vti", "transfer_function": {"opacity": [[0, 2]]}}})
scene("transfer_function_index_below_one", medium={"volume": {
    "file": "scalars.vti", "transfer_function": {"opacity": [[0, 0.5]],
                                                 "refractive_index": [[0, 0.5]]}}})
scene("transfer_function_tiny_unit", medium={"volume": {
    "file": "scalars.vti", "transfer_function": {"opacity": [[0, 0.999]], "unit_distance": 1e-30,
                                                 "emission_scale": 1e30}}})
scene("transfer_function_missing_array", medium={"volume": {
    "file": "scalars.vti", "array": "nope", "transfer_function": {"opacity": [[0, 0.5]]}}})
write(S, "not_an_object.json", "[1, 2, 3]\n")
write(S, "medium_is_a_string.json", '{"medium": "fog"}\n')
write(S, "meshes_not_objects.json", '{"medium": {"meshes": [1, "two", null]}}\n')
write(S, "lights_not_array.json", '{"medium": {"meshes": [{"sphere": {}}]}, "lights": {}}\n')
write(S, "numbers_as_strings.json", '{"image": {"width": "64"}}\n')
write(S, "deep_nesting.json", '{"effects": ' + "[" * 400 + "]" * 400 + "}\n")
write(S, "duplicate_keys.json", '{"image": {"width": 8, "width": -1}}\n')
write(S, "truncated.json", '{"image": {"width": 8, "hei')
write(S, "utf8_key.json", '{"m\\u00e9dium": {}}\n')
write(S, "big_integer.json", '{"image": {"width": 18446744073709551615}}\n')
write(S, "negative_zero_dims.json", json.dumps(
    {"medium": {"grid": {"dimensions": [-0.0, 4, 4]}, "meshes": [{"sphere": {}}]}}) + "\n")
