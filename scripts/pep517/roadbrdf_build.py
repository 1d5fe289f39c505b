"""PEP 517 build backend of roadbrdf: CMake builds the program and the Python extension, and the
wheel is assembled here with the standard library only (see pyproject.toml for why).

Wheel contents (from `cmake --install` of the components `program` and `python`):
  roadbrdf/                              the Python package with its extension
  roadbrdf-V.data/scripts/roadbrdf       the command-line program (pip puts it in <prefix>/bin)
  roadbrdf-V.data/data/share/...         data tables and man page (into <prefix>/share)
The program and the extension find the data relative to themselves (src/roadbrdf/core/data_path.h).

Settings: $ROADBRDF_PIP_BUILD_DIR (or config setting `build-dir`) names the CMake build folder; an
already configured folder is reused as it is (the test suite installs from its own build tree this
way). The default is build-pip/ in the source tree. $ROADBRDF_PIP_JOBS sets the build parallelism.
"""
import base64
import hashlib
import os
import re
import shutil
import subprocess
import sys
import sysconfig
import tarfile
import tempfile
import zipfile

_SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
_NAME = "roadbrdf"
_SUMMARY = "Spectral BRDF models, fitting, mixing, solar albedo and road photometry for road materials"


def _version():
    with open(os.path.join(_SOURCE, "CMakeLists.txt"), encoding="utf-8") as f:
        m = re.search(r"project\(roadbrdf VERSION ([0-9.]+)", f.read())
    if not m:
        raise RuntimeError("roadbrdf_build: no project(roadbrdf VERSION ...) in CMakeLists.txt")
    return m.group(1)


def _tag():
    python = "cp%d%d" % sys.version_info[:2]
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return f"{python}-{python}-{platform}"


def _metadata():
    return (f"Metadata-Version: 2.1\nName: {_NAME}\nVersion: {_version()}\nSummary: {_SUMMARY}\n"
            "Requires-Python: >=3.9\nRequires-Dist: numpy\nRequires-Dist: matplotlib\n"
            "Provides-Extra: dataframes\nRequires-Dist: pandas; extra == \"dataframes\"\n"
            "Provides-Extra: studies\nRequires-Dist: distributed; extra == \"studies\"\n")


def _wheel_file():
    return f"Wheel-Version: 1.0\nGenerator: roadbrdf_build\nRoot-Is-Purelib: false\nTag: {_tag()}\n"


def _dist_info():
    return f"{_NAME}-{_version()}.dist-info"


def _run(command, log):
    log.write("$ " + " ".join(command) + "\n")
    log.flush()
    result = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT)
    if result.returncode != 0:
        log.flush()
        with open(log.name, encoding="utf-8", errors="replace") as f:
            sys.stderr.write(f.read()[-20000:])
        raise RuntimeError(f"roadbrdf_build: command failed ({result.returncode}): {' '.join(command)}")


def _build_and_stage(config_settings, staging):
    settings = config_settings or {}
    build = settings.get("build-dir") or os.environ.get("ROADBRDF_PIP_BUILD_DIR") or os.path.join(_SOURCE, "build-pip")
    build = os.path.abspath(build)
    jobs = os.environ.get("ROADBRDF_PIP_JOBS", str(os.cpu_count() or 1))
    os.makedirs(build, exist_ok=True)
    with open(os.path.join(build, "pip-build.log"), "w", encoding="utf-8") as log:
        if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
            _run(["cmake", "-S", _SOURCE, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                  f"-DPYTHON_EXECUTABLE={sys.executable}", "-DROADBRDF_BUILD_TESTS=OFF",
                  "-DROADBRDF_BUILD_BENCHMARKS=OFF"], log)
        _run(["cmake", "--build", build, "-j", jobs, "--target", "roadbrdf", "_roadbrdf", "roadbrdf_manpage"], log)
        for component in ("program", "python"):
            _run(["cmake", "--install", build, "--prefix", staging, "--component", component], log)


def _record_line(arcname, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{arcname},sha256={digest},{len(data)}"


def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_sdist(config_settings=None):
    return []


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    dist_info = os.path.join(metadata_directory, _dist_info())
    os.makedirs(dist_info, exist_ok=True)
    with open(os.path.join(dist_info, "METADATA"), "w", encoding="utf-8") as f:
        f.write(_metadata())
    with open(os.path.join(dist_info, "WHEEL"), "w", encoding="utf-8") as f:
        f.write(_wheel_file())
    return _dist_info()


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    version = _version()
    data_dir = f"{_NAME}-{version}.data"
    wheel_name = f"{_NAME}-{version}-{_tag()}.whl"
    with tempfile.TemporaryDirectory() as staging:
        _build_and_stage(config_settings, staging)
        entries = []  # (arcname, file path or bytes, executable)
        package_root = None
        for root, _, files in os.walk(staging):
            if os.path.basename(root) == _NAME and os.path.exists(os.path.join(root, "__init__.py")):
                package_root = os.path.dirname(root)
        if package_root is None:
            raise RuntimeError("roadbrdf_build: the install staged no Python package")
        for root, _, files in os.walk(staging):
            for name in sorted(files):
                path = os.path.join(root, name)
                rel = os.path.relpath(path, staging)
                if path.startswith(package_root + os.sep):
                    arcname = os.path.relpath(path, package_root)
                elif rel.startswith("bin" + os.sep):
                    arcname = f"{data_dir}/scripts/{os.path.relpath(path, os.path.join(staging, 'bin'))}"
                elif rel.startswith("share" + os.sep):
                    arcname = f"{data_dir}/data/{rel}"
                else:
                    continue
                entries.append((arcname.replace(os.sep, "/"), path, os.access(path, os.X_OK)))
        dist_info = _dist_info()
        entries.append((f"{dist_info}/METADATA", _metadata().encode(), False))
        entries.append((f"{dist_info}/WHEEL", _wheel_file().encode(), False))
        os.makedirs(wheel_directory, exist_ok=True)
        target = os.path.join(wheel_directory, wheel_name)
        record = []
        with zipfile.ZipFile(target, "w", compression=zipfile.ZIP_DEFLATED) as wheel:
            for arcname, source, executable in entries:
                data = source if isinstance(source, bytes) else open(source, "rb").read()
                info = zipfile.ZipInfo(arcname, date_time=(2026, 1, 1, 0, 0, 0))
                info.compress_type = zipfile.ZIP_DEFLATED
                info.external_attr = ((0o755 if executable else 0o644) | 0o100000) << 16
                wheel.writestr(info, data)
                record.append(_record_line(arcname, data))
            record.append(f"{dist_info}/RECORD,,")
            wheel.writestr(f"{dist_info}/RECORD", "\n".join(record) + "\n")
    return wheel_name


def build_sdist(sdist_directory, config_settings=None):
    version = _version()
    base = f"{_NAME}-{version}"
    try:
        files = subprocess.run(["git", "-C", _SOURCE, "ls-files"], capture_output=True, text=True,
                               check=True).stdout.split()
    except (OSError, subprocess.CalledProcessError):
        files = []
        for root, dirs, names in os.walk(_SOURCE):
            dirs[:] = [d for d in dirs if d != ".git" and not d.startswith("build")]
            files += [os.path.relpath(os.path.join(root, n), _SOURCE) for n in names]
    os.makedirs(sdist_directory, exist_ok=True)
    target = os.path.join(sdist_directory, base + ".tar.gz")
    with tarfile.open(target, "w:gz") as tar:
        for rel in sorted(files):
            tar.add(os.path.join(_SOURCE, rel), arcname=f"{base}/{rel}", recursive=False)
        pkg_info = _metadata().encode()
        info = tarfile.TarInfo(f"{base}/PKG-INFO")
        info.size = len(pkg_info)
        import io
        tar.addfile(info, io.BytesIO(pkg_info))
    return base + ".tar.gz"
