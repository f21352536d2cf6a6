"""One writer per sweep store: a second sweep on a store being written is refused; a lock
left by a killed sweep is taken over; the lock is removed when the sweep ends."""

from __future__ import annotations

import socket
import subprocess
import sys

import pytest

from impactmaps.cli import main
from impactmaps.maps.files.store_lock import StoreLockedError, lock_path, store_lock

from ..helpers import SWEEP_CONFIG


def _dead_pid() -> int:
    """The id of a process that has exited (not reused within the test, in practice)."""
    done = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True)
    return int(done.stdout)


def test_second_writer_is_refused_and_the_lock_is_removed_after(tmp_path):
    store = tmp_path / "sweep.nc"
    with store_lock(store):
        assert lock_path(store).exists()
        with pytest.raises(StoreLockedError, match="being written by another sweep"):
            with store_lock(store):
                pass
    assert not lock_path(store).exists()


def test_lock_is_removed_when_the_writer_fails(tmp_path):
    store = tmp_path / "sweep.nc"
    with pytest.raises(KeyboardInterrupt):
        with store_lock(store):
            raise KeyboardInterrupt
    assert not lock_path(store).exists()


def test_lock_of_a_killed_writer_is_taken_over(tmp_path):
    store = tmp_path / "sweep.nc"
    lock_path(store).write_text(f"{socket.gethostname()} {_dead_pid()}\n")
    with store_lock(store):
        pass
    assert not lock_path(store).exists()


def test_lock_from_another_host_is_respected(tmp_path):
    store = tmp_path / "sweep.nc"
    lock_path(store).write_text("some-other-host 12345\n")
    with pytest.raises(StoreLockedError, match="some-other-host"):
        with store_lock(store):
            pass


def test_cli_sweep_on_a_locked_store_exits_2_naming_the_lock(tmp_path, capsys):
    """``impactmaps sweep`` while another live sweep (here: this test process) writes the store."""
    config = tmp_path / "sweep.toml"
    config.write_text(SWEEP_CONFIG)
    (tmp_path / "out").mkdir()
    lock = lock_path(tmp_path / "out" / "sweep.nc")
    lock.write_text(f"{socket.gethostname()} {__import__('os').getpid()}\n")
    assert main(["sweep", str(config), "--workers", "1", "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "being written by another sweep" in err and str(lock) in err and "Traceback" not in err
    assert lock.exists()  # the other writer's lock is left alone
    assert not (tmp_path / "out" / "sweep.nc").exists()


def test_cli_sweep_runs_and_leaves_no_lock(tmp_path, capsys):
    config = tmp_path / "sweep.toml"
    config.write_text(SWEEP_CONFIG)
    assert main(["sweep", str(config), "--workers", "1", "--quiet"]) == 0
    assert (tmp_path / "out" / "sweep.nc").exists()
    assert not lock_path(tmp_path / "out" / "sweep.nc").exists()
