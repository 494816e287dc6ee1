"""The on-disk cache: hits, misses, corruption, staleness, concurrent writers, bad disks."""
import errno
import io
import logging
import multiprocessing
import os
import shutil
import threading
import tracemalloc

import numpy as np
import pytest

from model import Params, SolverOptions
from model.runs import cache as cache_mod
from model.runs import cache_keys
from model.runs.cache import DiskCache, make_key


def _key(**changes):
    settings = dict(params=Params(k_r=3.0, k_theta=0.01), tol=1e-3,
                    options=SolverOptions(rtol=1e-6))
    settings.update(changes)
    return make_key("uniform_array", **settings)


def _arrays(seed=0):
    rng = np.random.default_rng(seed)
    return {"F": rng.normal(size=(7, 5)), "n": np.arange(4, dtype=np.int32),
            "ok": np.array([True, False])}


class Counter:
    """A compute function that counts its calls."""

    def __init__(self, seed=0):
        self.calls, self.seed = 0, seed

    def __call__(self):
        self.calls += 1
        return _arrays(self.seed), {"seconds": 1.5}


@pytest.fixture
def cache(tmp_path):
    return DiskCache(tmp_path)


def _assert_same(a, b):
    assert sorted(a) == sorted(b)
    for name in a:
        assert a[name].dtype == b[name].dtype and a[name].shape == b[name].shape
        np.testing.assert_array_equal(a[name], b[name])


def test_hit_returns_identical_arrays(cache):
    compute = Counter()
    first = cache.get_or_compute(_key(), compute)
    second = cache.get_or_compute(_key(), compute)
    assert compute.calls == 1
    _assert_same(first, _arrays())
    _assert_same(second, _arrays())
    # A fresh object on the same folder (another process, later) hits too.
    again = DiskCache(cache.root).load(_key())
    assert again is not None and again[1] == {"seconds": 1.5}
    _assert_same(again[0], _arrays())


def test_location_from_environment(tmp_path, monkeypatch):
    monkeypatch.setenv("MICROPILLAR_CACHE_DIR", str(tmp_path / "env"))
    c = DiskCache()
    assert c.path == tmp_path / "env" / f"v{c.version}"
    assert c.put(_key(), _arrays())
    assert c.file_for(_key()).parent == c.path and c.file_for(_key()).exists()


@pytest.mark.parametrize("change", [
    dict(params=Params(k_r=3.0, k_theta=0.02)),          # a parameter
    dict(params=Params(k_r=3.0, k_theta=0.01, F_N=2.0)),  # the load
    dict(tol=1e-4),                                       # a quadrature setting
    dict(options=SolverOptions(rtol=1e-7)),               # a solver setting
    dict(options=SolverOptions(rtol=1e-6, method="implicit")),
])
def test_changed_setting_misses(cache, change):
    cache.put(_key(), _arrays())
    assert cache.get(_key()) is not None
    assert cache.get(_key(**change)) is None
    assert cache.file_for(_key(**change)) != cache.file_for(_key())


def test_key_order_does_not_matter(cache):
    cache.put({"a": 1, "b": [1.5, 2]}, _arrays())
    assert cache.get({"b": [1.5, 2], "a": 1}) is not None


@pytest.mark.parametrize("damage", ["truncate", "flip", "garbage", "empty"])
def test_corrupted_file_is_detected_and_recomputed(cache, caplog, damage):
    cache.put(_key(), _arrays())
    path = cache.file_for(_key())
    data = bytearray(path.read_bytes())
    if damage == "truncate":
        data = data[: len(data) // 2]
    elif damage == "flip":
        for i in range(len(data) // 3, len(data) // 3 + 8):  # inside the first array's data
            data[i] ^= 0xFF
    elif damage == "garbage":
        data = bytearray(b"not a zip file at all" * 10)
    else:
        data = bytearray()
    path.write_bytes(bytes(data))

    compute = Counter(seed=1)
    with caplog.at_level(logging.WARNING, logger="model.runs.cache"):
        result = cache.get_or_compute(_key(), compute)
    assert compute.calls == 1, "a damaged file must not be returned"
    _assert_same(result, _arrays(seed=1))
    assert any("invalid" in r.getMessage() for r in caplog.records)
    _assert_same(cache.get(_key()), _arrays(seed=1))  # rewritten and valid again


def test_checksum_catches_tampered_values(cache, caplog):
    """Rewriting an entry with other values but the old checksum (valid zip) is caught."""
    cache.put(_key(), _arrays())
    path = cache.file_for(_key())
    with np.load(path) as npz:
        contents = {name: npz[name] for name in npz.files}
    contents["F"] = contents["F"] + 1e-12
    with open(path, "wb") as f:
        np.savez(f, **contents)
    with caplog.at_level(logging.WARNING, logger="model.runs.cache"):
        assert cache.get(_key()) is None
    assert any("checksum" in r.getMessage() for r in caplog.records)
    assert not path.exists()


def test_stale_version_is_recomputed(tmp_path, caplog):
    old = DiskCache(tmp_path, version="0.0.9")
    new = DiskCache(tmp_path)
    assert old.path != new.path  # each version has its own folder
    old.put(_key(), _arrays())
    assert new.get(_key()) is None
    # An old file found under the new name (e.g. copied over) is stale, not a hit.
    new.path.mkdir(parents=True, exist_ok=True)
    shutil.copy(old.file_for(_key()), new.file_for(_key()))
    compute = Counter(seed=2)
    with caplog.at_level(logging.WARNING, logger="model.runs.cache"):
        result = new.get_or_compute(_key(), compute)
    assert compute.calls == 1
    _assert_same(result, _arrays(seed=2))
    assert any("stale" in r.getMessage() and "0.0.9" in r.getMessage() for r in caplog.records)


def test_stale_key_is_recomputed(cache, caplog):
    cache.put(_key(), _arrays())
    other = _key(tol=1e-5)
    cache.path.joinpath(cache.file_for(other).name).write_bytes(cache.file_for(_key()).read_bytes())
    with caplog.at_level(logging.WARNING, logger="model.runs.cache"):
        assert cache.get(other) is None
    assert any("stored key differs" in r.getMessage() for r in caplog.records)


def _writer(directory, seed, rounds):
    c = DiskCache(directory)
    for i in range(rounds):
        c.put(_key(), _arrays(seed), {"writer": seed, "round": i})


def test_concurrent_writers_leave_a_valid_file(cache, caplog):
    ctx = multiprocessing.get_context("fork" if hasattr(os, "fork") else "spawn")
    procs = [ctx.Process(target=_writer, args=(cache.root, seed, 150)) for seed in (10, 11)]
    for p in procs:
        p.start()
    with caplog.at_level(logging.WARNING, logger="model.runs.cache"):
        while any(p.is_alive() for p in procs):  # read while they write: never a partial file
            got = cache.get(_key())
            if got is not None:
                assert any(np.array_equal(got["F"], _arrays(s)["F"]) for s in (10, 11))
    assert caplog.records == [], "a reader saw an invalid file"
    for p in procs:
        p.join(30)
        assert p.exitcode == 0
    arrays, meta = cache.load(_key())
    _assert_same(arrays, _arrays(meta["writer"]))
    assert meta["round"] == 149
    assert [p.name for p in cache.path.iterdir()] == [cache.file_for(_key()).name]  # no temp files


def test_unwritable_directory_degrades_with_one_warning(tmp_path, caplog, monkeypatch):
    """A read-only cache folder. The suite runs as root in CI, where chmod does not stop
    writes, so the refusal (EROFS) is raised by monkeypatching the temp-file creation."""
    c = DiskCache(tmp_path / "ro")
    c.path.mkdir(parents=True)

    def refuse(*args, **kwargs):
        raise OSError(errno.EROFS, "Read-only file system (simulated)")

    monkeypatch.setattr(cache_mod.tempfile, "mkstemp", refuse)
    compute = Counter()
    with caplog.at_level(logging.WARNING, logger="model.runs.cache"):
        for _ in range(3):
            _assert_same(c.get_or_compute(_key(), compute), _arrays())
    assert compute.calls == 3 and not c.writable
    warnings = [r for r in caplog.records if r.levelno == logging.WARNING]
    assert len(warnings) == 1 and "not writable" in warnings[0].getMessage()
    assert list(c.path.iterdir()) == []


def test_disk_full_degrades_and_leaves_no_temp_file(cache, caplog, monkeypatch):
    def full(*args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device (simulated)")
    monkeypatch.setattr(cache_mod.os, "fsync", full)
    with caplog.at_level(logging.WARNING, logger="model.runs.cache"):
        assert cache.put(_key(), _arrays()) is False
        assert cache.put(_key(tol=1e-4), _arrays()) is False
    assert len(caplog.records) == 1
    assert list(cache.path.iterdir()) == []


def test_size_bound_evicts_least_recently_used(tmp_path):
    c = DiskCache(tmp_path, max_entries=3)
    keys = [_key(tol=10.0 ** -i) for i in range(1, 6)]
    for i, k in enumerate(keys):
        c.put(k, _arrays())
        os.utime(c.file_for(k), (1000.0 + i, 1000.0 + i))  # distinct, increasing mtimes
    assert len(c.entries()) == 3
    assert [c.get(k) is None for k in keys] == [True, True, False, False, False]
    small = DiskCache(tmp_path / "bytes", max_bytes=1)
    small.put(keys[0], _arrays())
    assert small.entries() == []


def test_clear_and_bad_input(cache):
    cache.put(_key(), _arrays())
    cache.put(_key(tol=1e-4), _arrays())
    assert cache.clear() == 2 and cache.entries() == []
    with pytest.raises(ValueError):
        cache.put(_key(), {"__key__": np.zeros(1)})
    with pytest.raises(TypeError):
        cache.put(_key(), {"x": np.array([object()])})
    with pytest.raises(TypeError):
        cache.put({"f": object()}, _arrays())
    with pytest.raises(ValueError):
        cache.put({"x": float("nan")}, _arrays())


def test_changed_model_code_misses(cache, monkeypatch):
    cache.put(_key(), {"a": np.arange(3.0)})
    assert cache.get(_key()) is not None
    monkeypatch.setattr(cache_keys, "code_digest", lambda: "edited-code")
    assert cache.get(_key()) is None  # results of other code are never returned


def test_code_digest_covers_computing_code_but_not_the_report_and_cli():
    from pathlib import Path

    root = Path(cache_mod.__file__).parents[1]  # the model package
    covered = {p.relative_to(root).parts[0] for p in root.rglob("*.py")} - set(
        cache_keys.PRESENTATION)
    assert {"arrays", "contact", "designs", "lab", "runs", "_kernel", "controls.py"} <= covered
    assert {"reproduce", "cli"} <= {p.name for p in root.iterdir()}


# --------------------------------------------------------------------------- hostile folders

def _zip_bomb(path, key_json, unpacked: int):
    """An entry whose array member is ``unpacked`` bytes of zeros, deflated to ~1/1000."""
    import zipfile

    header = io.BytesIO()
    np.lib.format.write_array_header_1_0(
        header, {"descr": "<f8", "fortran_order": False, "shape": (unpacked // 8,)})
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        with archive.open("F.npy", "w", force_zip64=True) as member:
            member.write(header.getvalue())
            chunk = bytes(1 << 20)
            for _ in range(unpacked // len(chunk)):
                member.write(chunk)
        for name, text in (("__key__", key_json), ("__meta__", "{}"), ("__version__", "x"),
                           ("__checksum__", "0")):
            buf = io.BytesIO()
            np.save(buf, np.array(text))
            archive.writestr(name + ".npy", buf.getvalue())


def test_oversize_entry_is_refused_before_it_is_unpacked(cache, caplog):
    """0.06 MB on disk that would unpack to 64 MB: refused from the declared sizes, so the
    read allocates next to nothing (it used to build the whole array first)."""
    path = cache.file_for(_key())
    cache.path.mkdir(parents=True)
    _zip_bomb(path, cache_mod.canonical_json(_key()), 64 * 1024**2)
    on_disk = path.stat().st_size
    assert on_disk < 200_000
    tracemalloc.start()
    try:
        with caplog.at_level(logging.WARNING, logger="model.runs.cache"):
            assert cache.get(_key()) is None
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 4 * on_disk + 500_000, f"{peak} bytes allocated to refuse {on_disk} bytes"
    assert any("more than" in r.getMessage() for r in caplog.records)
    assert not path.exists()  # discarded like any invalid entry


def test_entry_larger_than_the_bound_on_disk_is_not_read(tmp_path, caplog):
    small = DiskCache(tmp_path, max_entry_bytes=10_000)
    assert small.put(_key(), _arrays())
    assert small.get(_key()) is not None
    big = {"F": np.zeros(5_000)}  # 40 kB: beyond the bound, so not written either
    assert small.put(_key(tol=1e-4), big) is False and small.writable
    DiskCache(tmp_path).put(_key(tol=1e-4), big)  # written by a cache with a larger bound
    with caplog.at_level(logging.WARNING, logger="model.runs.cache"):
        assert small.get(_key(tol=1e-4)) is None
    assert any("more than the 10000" in r.getMessage() for r in caplog.records)


def _get_within(cache, key, seconds=10.0):
    """``cache.get(key)`` in a thread; fails the test if it has not returned in time."""
    result = {}
    reader = threading.Thread(target=lambda: result.setdefault("value", cache.get(key)),
                              daemon=True)
    reader.start()
    reader.join(seconds)
    if reader.is_alive():
        pytest.fail(f"cache.get blocked for more than {seconds:.0f} s")
    return result["value"]


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes on this system")
def test_named_pipe_at_an_entry_is_a_miss_not_a_hang(cache):
    cache.path.mkdir(parents=True)
    os.mkfifo(cache.file_for(_key()))
    assert _get_within(cache, _key()) is None
    compute = Counter()
    _assert_same(cache.get_or_compute(_key(), compute), _arrays())
    assert compute.calls == 1 and cache.file_for(_key()).is_file()  # the pipe was replaced
    _assert_same(_get_within(cache, _key()), _arrays())


def test_folder_at_an_entry_skips_that_entry_only(cache, caplog):
    cache.path.mkdir(parents=True)
    blocker = cache.file_for(_key())
    blocker.mkdir()
    (blocker / "inside").write_text("x")
    with caplog.at_level(logging.WARNING, logger="model.runs.cache"):
        assert _get_within(cache, _key()) is None
        assert cache.put(_key(), _arrays()) is False
    assert cache.writable and DiskCache(cache.root).writable  # caching stays on
    assert cache.put(_key(tol=1e-4), _arrays())
    _assert_same(cache.get(_key(tol=1e-4)), _arrays())
    assert blocker.is_dir() and not list(cache.path.glob("*.tmp"))


@pytest.mark.skipif(not hasattr(os, "symlink"), reason="no symbolic links on this system")
def test_symbolic_link_at_an_entry_is_not_followed(cache, tmp_path):
    cache.put(_key(), _arrays())
    elsewhere = tmp_path / "elsewhere.npz"
    cache.file_for(_key()).rename(elsewhere)
    cache.file_for(_key()).symlink_to(elsewhere)
    assert cache.get(_key()) is None
    assert elsewhere.exists()  # the link was removed, never its target


def test_entries_are_still_checksummed_after_the_bounded_read(cache):
    cache.put(_key(), _arrays())
    _assert_same(cache.get(_key()), _arrays())
    got = cache.get(_key())
    got["F"][0, 0] = 42.0  # arrays come back writable, as numpy.load gives them
    assert cache.get(_key())["F"][0, 0] != 42.0


def test_writes_do_not_scan_the_folder_each_time(tmp_path, monkeypatch):
    """Eviction used to stat every entry on every write (144 ms a write at 10 000
    entries): now a scan comes once per tenth of the bound's worth of writes."""
    c = DiskCache(tmp_path, max_entries=100)
    for i in range(60):
        c.put(_key(tol=1e-3 + i * 1e-6), _arrays())
    scans = []
    real = os.scandir

    def counting(path):
        scans.append(path)
        return real(path)

    monkeypatch.setattr(cache_mod.os, "scandir", counting)
    writes = 100
    for i in range(writes):
        c.put(_key(tol=2e-3 + i * 1e-6), _arrays())
    assert 1 <= len(scans) <= writes // 10 + 1, len(scans)
    assert len(c.entries()) <= c.max_entries  # still bounded
    newest = [_key(tol=2e-3 + i * 1e-6) for i in range(writes - 5, writes)]
    assert all(c.get(k) is not None for k in newest)  # and the newest kept
