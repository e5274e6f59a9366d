"""Imports the wrc module from an install directory (and only from there) and checks the
consumers' value and the version: check_installed.py MODULE_DIR TABLE VERSION
(tests/integration/consumer/expected.h)."""

import sys

module_dir, table, version = sys.argv[1:4]
sys.path.insert(0, module_dir)
import wrc  # noqa: E402

assert wrc.__file__.startswith(module_dir), wrc.__file__
assert wrc.__version__ == version, (wrc.__version__, version)
fx = wrc.Table(table).eval([0.5, 0.005])[0, 0]
assert abs(fx - 3.625) <= 1e-12, fx
print("installed wrc module:", wrc.__file__, "fx =", fx)
