"""shlab — real spherical harmonics, from Python (ctypes over libshlab.so).

One module per concept; the main calls are re-exported here:

- basis:    eval_angles, eval_dir (sh_eval, sh_eval_dir), dir_from_angles, angles_from_dir
- convert:  convert, convert_inplace, convention_switch (sh_convert, sh_convention_switch)
- project:  Light, project_light, project_function, project_image, project_exr,
            green_reference, cap_zonal, lobe_zonal
- image:    read_exr, write_exr, pixel_solid_angles
- rotation: Rotation (from_euler / from_quat / from_matrix / from_axis_angle)
- rotate:   Rotator, Plan (apply_many, rotate_many), Stream, rotate_band, rotation_matrix
- verify:   load_fixture, verify, simulate, load_candidate, apply_method, mistakes
- identify: Convention (parse, str, preset), convert_convention, to_shlab, from_shlab,
            eval_convention, identify_basis, identify_projection, fixture_directions,
            fixture_light, fixture_light_coeffs (sh_conv_*, sh_identify_*: `shlab identify`)

Every failing shlab call raises :class:`shlab.Error` (message from
sh_last_error(), ``status`` the code).  Conventions: docs/CONVENTIONS.md
(installed as share/doc/shlab/CONVENTIONS.md); this package: docs/python.md.
"""
from ._lib import Error, library_path
from .basis import angles_from_dir, dir_from_angles, eval_angles, eval_dir
from .convert import convention_switch, convention_switch_inplace, convert, convert_inplace
from .image import pixel_solid_angles, read_exr, write_exr
from .project import (Light, cap_zonal, green_reference, image_max_order, lobe_zonal, project_exr,
                      project_function, project_image, project_light)
from .rotate import Plan, Rotator, Stream, kernel_available, method_max_order, rotate_band, rotation_matrix
from .rotation import Rotation
from .verify import (Fixture, VerifyResult, apply_method, load_candidate, load_fixture, mistake_description,
                     mistakes, simulate, verify)
from .verify import available as verify_available
from .identify import (Candidate, Convention, IdentifyResult, convert_convention, eval_convention,
                       fixture_directions, fixture_light, fixture_light_coeffs, from_shlab, identify_basis,
                       identify_projection, to_shlab)
from .identify import available as identify_available

__version__ = "0.1.0"  # SHLAB_VERSION of src/shlab.h

__all__ = ["Error", "library_path", "eval_angles", "eval_dir", "dir_from_angles", "angles_from_dir", "convert",
           "convert_inplace", "convention_switch", "convention_switch_inplace", "read_exr", "write_exr",
           "pixel_solid_angles", "Light", "project_light", "project_function", "project_image", "project_exr",
           "green_reference", "cap_zonal", "lobe_zonal", "image_max_order", "Rotation", "Rotator", "Plan",
           "Stream", "rotate_band", "rotation_matrix", "method_max_order", "kernel_available", "load_fixture",
           "verify", "simulate", "load_candidate", "apply_method", "mistakes", "mistake_description",
           "Fixture", "VerifyResult", "verify_available", "Convention", "convert_convention", "to_shlab",
           "from_shlab", "eval_convention", "identify_basis", "identify_projection", "fixture_directions",
           "fixture_light", "fixture_light_coeffs", "IdentifyResult", "Candidate", "identify_available"]
