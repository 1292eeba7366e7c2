"""Kernels compiled ahead and shipped in the package: a new machine's first run loads them.

Compiling the engine from an empty cache is most of a first run (all the lessons: about half
of 80 to 120 s on the project's 2-core machine). numba caches machine code for the processor
it runs on, but it can also compile for a named processor family. Code for ``x86-64-v3`` (the
instructions of x86-64 processors since about 2015: AVX2, FMA, BMI) runs on every such
processor, so it can be compiled once, when the package is built, and shipped in it
(``python -m sandbox.prebuilt`` writes it into :data:`ARCHIVE`, which the wheel then carries).
Measured on the project's machine (AVX-512): the lessons' outputs were the same to the byte as
with code for the machine itself (their timing tables aside: no instruction changes what it
computes, only how many numbers it works on at once), and the step benchmarks 4 to 19 % slower
(the wide sweeps do four contacts at once instead of eight).

On a machine where :func:`matches` (the same numba, Python, system and kernel sources as the
build, and a processor that runs the target's instructions), the cache for the machine's own
processor is not warm and numba's code generation is not set by hand (:data:`USERS_CHOICE`),
:func:`use` unpacks the shipped kernels into a cache folder of their own
beside that one and points numba there (``NUMBA_CPU_NAME``), for this process and the ones it
starts. ``sandbox warmup`` compiles for the machine itself as before, and from then on that
cache is used. ``SANDBOX_PREBUILT=off`` leaves the shipped kernels alone.

numba finds a function's cached code in a folder named after the folder of its source file
(:func:`numba_folder_name`), so the shipped copy keeps the package's folders by their place in
the package (``solvers``, ``narrowphase`` ...) and gets numba's names where it is installed.
numba checks each function against a hash of its source, and the whole cache folder is named
after a hash of every kernel's source (:mod:`sandbox.compile_cache`), so an edited package
never loads the shipped code of another.

Nothing here imports numba: :mod:`sandbox.compile_cache` decides before the engine loads.
"""

from __future__ import annotations

import hashlib
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import zipfile
from collections.abc import MutableMapping
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

TARGET = "x86-64-v3"  # the processor family the shipped kernels are compiled for
# what /proc/cpuinfo lists for a processor that runs x86-64-v3 code (lzcnt shows as abm)
TARGET_FLAGS = frozenset(
    "cx16 lahf_lm popcnt sse4_1 sse4_2 ssse3 avx avx2 bmi1 bmi2 f16c fma abm movbe xsave".split()
)
# as Python imported it, links not followed: numba names its folders after this path
PACKAGE = Path(os.path.abspath(__file__)).parent
# the shipped kernels, one file (a folder of data in the package would look like a package of
# Python to the wheel's builder): KERNELS and MANIFEST
ARCHIVE = PACKAGE / "prebuilt_kernels.zip"
KERNELS = "kernels"  # in ARCHIVE: the cache's files, in the package's folders (shipped_name)
MANIFEST = "manifest.json"  # in ARCHIVE: what they were compiled with (this_build())
SWITCH = "SANDBOX_PREBUILT"  # "off": never use the shipped kernels
IN_USE = "SANDBOX_PREBUILT_IN_USE"  # set for the processes a process using them starts
# numba's settings that change the code it makes, which its cache does not tell apart: any of
# them set, the code is compiled here as asked (array bounds checked, another target ...)
USERS_CHOICE = ("NUMBA_CPU_NAME", "NUMBA_CPU_FEATURES", "NUMBA_BOUNDSCHECK", "NUMBA_OPT")


def this_build(kernels: str) -> dict[str, str]:
    """What shipped kernels must have been compiled with to run here, for the kernel sources
    of hash ``kernels`` (:func:`sandbox.compile_cache.kernel_sources_hash`)."""
    try:
        numba = version("numba")
    except PackageNotFoundError:
        numba = "none"
    return {
        "numba": numba,
        "python": sys.implementation.cache_tag or "",
        "platform": sys.platform,
        "machine": platform.machine(),
        "kernels": kernels,
        "target": TARGET,
    }


def runs_target(cpuinfo: str | None = None) -> bool:
    """Whether this processor runs :data:`TARGET` code: every flag of :data:`TARGET_FLAGS` in
    ``/proc/cpuinfo`` (or in ``cpuinfo``, its text). False where there is no such file."""
    if cpuinfo is None:
        try:
            cpuinfo = Path("/proc/cpuinfo").read_text()
        except OSError:
            return False
    for line in cpuinfo.splitlines():
        if line.startswith("flags"):
            return TARGET_FLAGS <= set(line.partition(":")[2].split())
    return False


def matches(kernels: str, archive: Path | None = None) -> bool:
    """Whether ``archive`` (default :data:`ARCHIVE`) holds shipped kernels that run here (see
    the module)."""
    try:
        with zipfile.ZipFile(ARCHIVE if archive is None else archive) as shipped_kernels:
            shipped = json.loads(shipped_kernels.read(MANIFEST))
    except (OSError, ValueError, KeyError, zipfile.BadZipFile):
        return False
    return shipped == this_build(kernels) and runs_target()


def numba_folder_name(directory: Path) -> str:
    """The folder numba keeps the cached code of the functions in ``directory``'s source files
    in, below its cache folder (numba's ``_CacheLocator.get_suitable_cache_subpath``): the
    folder's name and a hash of its absolute path."""
    path = os.path.abspath(directory)
    return f"{os.path.basename(path)}_{hashlib.sha1(path.encode()).hexdigest()}"


def package_folders(package: Path = PACKAGE) -> dict[str, str]:
    """numba's name (:func:`numba_folder_name`) -> the name the shipped kernels keep the
    folder's code under (its place in ``package``, dotted: ``sandbox``, ``sandbox.solvers``),
    for the package and each folder of Python sources in it."""
    folders = [package, *(p.parent for p in package.rglob("*/*.py") if "." not in p.parent.name)]
    return {numba_folder_name(p): shipped_name(p.relative_to(package)) for p in folders}


def shipped_name(place: Path) -> str:
    """The name of a package folder's code among the shipped kernels (``place``: the folder's
    path in the package, ``.`` for the package itself)."""
    return ".".join(["sandbox", *place.parts])


def package_folder(name: str, package: Path = PACKAGE) -> Path:
    """The folder of ``package`` whose code the shipped kernels keep under ``name``."""
    return package.joinpath(*name.split(".")[1:])


def install(dest: Path, archive: Path | None = None, package: Path = PACKAGE) -> bool:
    """Unpack the shipped kernels in ``archive`` (default :data:`ARCHIVE`) into the cache
    folder ``dest`` under numba's names for ``package``'s folders, once (a folder already marked
    warm is kept), whole or not at all (unpacked beside it, then renamed). Returns whether
    ``dest`` holds them."""
    from sandbox.compile_cache import WARM_FILE  # here: compile_cache imports this module

    if (dest / WARM_FILE).exists():
        return True
    work = None
    try:
        dest.parent.mkdir(parents=True, exist_ok=True)
        work = Path(tempfile.mkdtemp(prefix=dest.name + ".", dir=dest.parent))
        with zipfile.ZipFile(ARCHIVE if archive is None else archive) as shipped_kernels:
            for member in shipped_kernels.infolist():
                top, name, file = (member.filename.split("/") + ["", ""])[:3]
                if top != KERNELS or not name.startswith("sandbox") or not file:
                    continue  # the manifest, or nothing of ours
                folder = work / numba_folder_name(package_folder(name, package))
                folder.mkdir(exist_ok=True)
                (folder / Path(file).name).write_bytes(shipped_kernels.read(member))
        (work / WARM_FILE).write_text(f"kernels compiled for {TARGET}, shipped in the package\n")
        if not (dest / WARM_FILE).exists():  # a partial copy (never one another process made)
            shutil.rmtree(dest, ignore_errors=True)
        os.replace(work, dest)
    except (OSError, KeyError, zipfile.BadZipFile):  # not writable, or another process's first
        if work is not None:
            shutil.rmtree(work, ignore_errors=True)
        return (dest / WARM_FILE).exists()
    return True


def use(native: Path, kernels: str) -> Path | None:
    """The cache folder to use instead of ``native`` (the cache for this very processor, not
    warm): the shipped kernels' (see the module), installed beside it, or None. Sets numba's
    target in the environment, for this process and the ones it starts; a process started by
    one that used them, which is not to (its native cache warm, or ``SANDBOX_PREBUILT=off``),
    gets the environment back as it was."""
    ours = os.environ.get(IN_USE) == "1"
    if os.environ.get(SWITCH) == "off" or not matches(kernels):
        if ours:
            leave()
        return None
    if not ours and any(os.environ.get(name) for name in USERS_CHOICE):
        return None  # the user chose how numba compiles (its target, checks): theirs
    dest = native.parent / f"{native.name}-{TARGET}"
    if not install(dest):
        return None
    os.environ.update({"NUMBA_CPU_NAME": TARGET, "NUMBA_CPU_FEATURES": "", IN_USE: "1"})
    return dest


def leave(environ: MutableMapping[str, str] | None = None) -> None:
    """Take the shipped kernels' settings out of ``environ`` (default: this process's)."""
    environ = os.environ if environ is None else environ
    if environ.get(IN_USE) == "1":
        for name in ("NUMBA_CPU_NAME", "NUMBA_CPU_FEATURES", IN_USE):
            environ.pop(name, None)


def build(dest: Path | None = None) -> None:
    """Compile every kernel for :data:`TARGET` (``sandbox warmup`` in a process of its own, an
    empty cache) and write them into the archive ``dest`` (default :data:`ARCHIVE`) with their
    :data:`MANIFEST`, replacing what was there."""
    from sandbox.compile_cache import WARM_FILE, kernel_sources_hash

    key = kernel_sources_hash()
    with tempfile.TemporaryDirectory() as cache:
        command = [sys.executable, "-m", "sandbox", "warmup", "--quiet"]
        # cwd: the cache, so that no other folder named sandbox is imported first
        subprocess.run(command, env=target_environment(cache), cwd=cache, check=True)
        compiled = Path(cache) / f"numba-{key}"
        if not (compiled / WARM_FILE).exists():
            raise RuntimeError(f"the warmup left no warm cache in {compiled}")
        ship(compiled, ARCHIVE if dest is None else dest, key)


def target_environment(cache: str) -> dict[str, str]:
    """This process's environment for a process that compiles for :data:`TARGET` into the
    cache folder ``cache`` (``NUMBA_CACHE_DIR``), never into the shipped kernels' folder."""
    env = {k: v for k, v in os.environ.items() if k not in (IN_USE, "SANDBOX_JIT")}
    env.update({"NUMBA_CACHE_DIR": cache, "NUMBA_CPU_NAME": TARGET, "NUMBA_CPU_FEATURES": ""})
    env.update({SWITCH: "off", "SANDBOX_WARMUP": "off"})
    return env


def ship(compiled: Path, dest: Path, key: str) -> None:
    """Write the cache folder ``compiled`` (kernels compiled for :data:`TARGET`, sources of hash
    ``key``) into the archive ``dest`` as shipped kernels: the package's folders by their place
    in it (:func:`shipped_name`), and the :data:`MANIFEST`."""
    places = package_folders()
    work = dest.with_name(dest.name + ".part")
    with zipfile.ZipFile(work, "w", zipfile.ZIP_DEFLATED) as shipped_kernels:
        shipped_kernels.writestr(MANIFEST, json.dumps(this_build(key), indent=1) + "\n")
        for folder in sorted(p for p in compiled.iterdir() if p.is_dir()):
            for file in sorted(folder.iterdir()):
                shipped_kernels.write(file, f"{KERNELS}/{places[folder.name]}/{file.name}")
    os.replace(work, dest)


if __name__ == "__main__":
    _dest = Path(sys.argv[1]) if len(sys.argv) > 1 else ARCHIVE
    build(_dest)
    print(f"every kernel compiled for {TARGET} into {_dest}")
