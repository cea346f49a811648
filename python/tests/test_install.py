"""`cmake --install` puts a package that imports and works from the prefix alone."""

import os
import shutil
import subprocess
import sys

import pytest

from conftest import BUILD


@pytest.mark.skipif(shutil.which("cmake") is None, reason="cmake not found")
def test_the_installed_package_imports_and_works(tmp_path):
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", str(BUILD), "--prefix", str(prefix)], check=True,
                   capture_output=True)
    package = prefix / "lib" / "python3" / "dist-packages"
    assert (package / "attend" / "__init__.py").is_file()
    script = ("import attend, numpy as np\n"
              "assert attend.__file__.startswith(%r), attend.__file__\n"
              "image = np.zeros((40, 60, 3), np.uint8); image[10:30, 20:40] = (0, 0, 255)\n"
              "s = attend.saliency(image, config={'features': [{'name': 'colour_contrast'}]})\n"
              "assert s.shape == (40, 60) and s[20, 30] > s[2, 2]\n"
              "print(attend.__version__)\n" % str(package))
    env = {key: value for key, value in os.environ.items() if key != "PYTHONPATH"}
    env["PYTHONPATH"] = str(package)
    result = subprocess.run([sys.executable, "-c", script], cwd=tmp_path, env=env,
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip()
