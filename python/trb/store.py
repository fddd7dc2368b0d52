"""Results on disk: part files while the sweep runs, one Parquet file at the end.

While a sweep runs, every batch of finished cases is written by the client as one small
Parquet file in `RESULTS.parquet.parts/` (written to a temporary name, then renamed, so a
part is whole or absent). At the end the parts and the cases reused from an earlier
`RESULTS.parquet` are combined into `RESULTS.parquet` (again through a rename), one row per
case, and the parts directory is removed.

A rerun with the same output reads the earlier results file and any parts left by an
interrupted run and reuses every case whose id (the hash of its full definition) is there with
a final status (`ok`, `refused`, `invalid`); only the others run.
"""

from __future__ import annotations

import json
import os
import shutil
import time
import uuid
from pathlib import Path

import pyarrow as pa
import pyarrow.parquet as pq

from .runner import FINAL_STATUSES

RESULT_FIELDS = [
    ("status", pa.string()),
    ("message", pa.string()),
    ("wall_time", pa.float64()),
    ("worker", pa.string()),
]


class Store:
    def __init__(self, out: Path, value_columns: list[str]):
        self.out = Path(out)
        self.parts = self.out.with_name(self.out.name + ".parts")
        self.value_columns = list(value_columns)
        self.schema = pa.schema(
            [("id", pa.string())] + [(c, pa.float64()) for c in self.value_columns] + RESULT_FIELDS
        )

    # -- reading -----------------------------------------------------------------------

    def _files(self) -> list[Path]:
        files = [self.out] if self.out.is_file() else []
        if self.parts.is_dir():
            files += sorted(self.parts.glob("part-*.parquet"))
        return files

    def finished(self) -> dict[str, dict]:
        """Records (id: {column: value}) of the cases already finished, from the results file
        and the parts. Files or rows that do not hold this sweep's columns are ignored."""
        names = self.schema.names
        found: dict[str, dict] = {}
        for f in self._files():
            try:
                table = pq.read_table(f)
            except (OSError, pa.ArrowException):
                continue
            if not set(names) <= set(table.column_names):
                continue
            for row in table.select(names).to_pylist():
                if row["status"] in FINAL_STATUSES:
                    found[row["id"]] = row
        return found

    # -- writing -----------------------------------------------------------------------

    def record_row(self, record: dict) -> dict:
        row = {"id": record["id"]}
        row.update({c: record["values"].get(c) for c in self.value_columns})
        row.update({k: record.get(k) for k, _ in RESULT_FIELDS})
        return row

    def write_part(self, records: list[dict]) -> Path:
        """One part file holding these records (each from `trb.runner.run_case`)."""
        self.parts.mkdir(parents=True, exist_ok=True)
        table = pa.Table.from_pylist([self.record_row(r) for r in records], schema=self.schema)
        name = f"part-{time.time_ns()}-{uuid.uuid4().hex[:8]}.parquet"
        tmp = self.parts / f".{name}.tmp"
        pq.write_table(table, tmp)
        os.replace(tmp, self.parts / name)
        return self.parts / name

    def combine(self, case_columns: list[tuple[str, pa.DataType]], rows: list[dict], metadata: dict) -> pa.Table:
        """Write the results file (case columns, values, results; one row per case; the
        metadata as the schema's key-value metadata, text as is, the rest as JSON) and remove
        the parts."""
        fields = [pa.field(n, t) for n, t in case_columns] + [f for f in self.schema if f.name != "id"]
        fields.insert(1, pa.field("id", pa.string()))
        meta = {k: v if isinstance(v, str) else json.dumps(v) for k, v in metadata.items()}
        schema = pa.schema(fields, metadata=meta)
        table = pa.Table.from_pylist(rows, schema=schema)
        self.out.parent.mkdir(parents=True, exist_ok=True)
        tmp = self.out.with_name(f".{self.out.name}.{uuid.uuid4().hex[:8]}.tmp")
        pq.write_table(table, tmp)
        os.replace(tmp, self.out)
        if self.parts.is_dir():
            shutil.rmtree(self.parts)
        return table
