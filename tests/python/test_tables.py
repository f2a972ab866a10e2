"""Tables as arrays: the points `sedwave show` prints, read only."""
import csv
import hashlib
import io
import math
import subprocess

import numpy as np

import sedwave
from conftest import ROOT

TABLE = ROOT / "data" / "tables" / "long_w3.h5"
STATUS = {"missing": 0, "ok": 1, "unresolved": 2, "failed": 3}


def test_table_equals_show_and_is_left_as_it_was(sedwave_command):
    before = hashlib.sha256(TABLE.read_bytes()).hexdigest()
    t = sedwave.read_table(TABLE)
    assert hashlib.sha256(TABLE.read_bytes()).hexdigest() == before
    shown = subprocess.run([sedwave_command, "show", "--values-only", str(TABLE)], capture_output=True, text=True,
                           check=True).stdout
    rows = list(csv.DictReader(io.StringIO("\n".join(l for l in shown.splitlines() if not l.startswith("#")))))
    assert len(rows) == t["alpha_hat"].size
    for row in rows:
        i = int(np.argmin(np.abs(np.log(t["gamma_hat"] / float(row["gamma_hat"])))))
        j = int(np.argmin(np.abs(np.log(t["omega_hat"] / float(row["omega_hat"])))))
        assert t["gamma_hat"][i] == float(row["gamma_hat"]) and t["omega_hat"][j] == float(row["omega_hat"])
        assert t["status"][i, j] == STATUS[row["status"]]
        for key in ("alpha_hat", "c_hat", "sigma_alpha_hat", "sigma_c_hat"):
            shown_value = float(row[key])
            assert (math.isnan(shown_value) and math.isnan(t[key][i, j])) or t[key][i, j] == shown_value, key
    assert t["metadata"]["engine"] == "sedwave-linear"
