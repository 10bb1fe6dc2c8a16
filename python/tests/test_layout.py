"""The ctypes declarations against the header: every struct's size and
every field's offset as the C compiler lays them out, and the enum values."""
import os
import shutil
import subprocess

import pytest

from neuv import _capi

ENUMS = {
    "NEUV_OK": _capi.OK, "NEUV_ERR_INPUT": _capi.ERR_INPUT, "NEUV_ERR_IO": _capi.ERR_IO,
    "NEUV_ERR_CANCELLED": _capi.ERR_CANCELLED, "NEUV_FLOAT64": _capi.FLOAT64, "NEUV_UINT32": _capi.UINT32,
    "NEUV_METHOD_NEURAL": _capi.METHODS["neural"], "NEUV_METHOD_LSCM": _capi.METHODS["lscm"],
    "NEUV_METHOD_HARMONIC": _capi.METHODS["harmonic"], "NEUV_PRESET_FAST": _capi.PRESETS["fast"],
    "NEUV_PRESET_PAPER": _capi.PRESETS["paper"],
}


def test_structs_match_the_header(header, tmp_path):
    cc = shutil.which(os.environ.get("CC", "cc"))
    if not cc:
        pytest.skip("no C compiler")
    lines = ['#include <stddef.h>', '#include <stdio.h>', '#include "neuv/neuv.h"', "int main(void) {"]
    expected = []
    for cname, struct in _capi.STRUCTS.items():
        lines.append(f'printf("{cname} %zu\\n", sizeof({cname}));')
        expected.append(f"{cname} {_capi.ctypes.sizeof(struct)}")
        for field, _ in struct._fields_:
            lines.append(f'printf("{cname}.{field} %zu\\n", offsetof({cname}, {field}));')
            expected.append(f"{cname}.{field} {getattr(struct, field).offset}")
    for name, value in ENUMS.items():
        lines.append(f'printf("{name} %d\\n", (int){name});')
        expected.append(f"{name} {value}")
    lines.append("return 0; }")
    (tmp_path / "layout.c").write_text("\n".join(lines))
    include = os.path.dirname(os.path.dirname(header))
    subprocess.run([cc, "-std=c99", "-I", include, str(tmp_path / "layout.c"), "-o", str(tmp_path / "layout")],
                   check=True)
    actual = subprocess.run([str(tmp_path / "layout")], check=True, capture_output=True, text=True).stdout
    assert actual.splitlines() == expected
