"""The bearing file's JSON Schema (presets/bearing.schema.json, draft 2020-12) as an editor
uses it: every preset and every estimated example bearing validates, and the mistakes the
reader refuses (a misspelt key, a wrong type, an unknown contact law) fail the schema too."""

import json
from pathlib import Path

import jsonschema
import pytest

REPO = Path(__file__).resolve().parents[2]
SCHEMA = json.loads((REPO / "presets" / "bearing.schema.json").read_text())
BEARINGS = sorted((REPO / "presets").glob("*.json")) + sorted((REPO / "examples" / "bearings").glob("*.json"))
BEARINGS = [p for p in BEARINGS if p.name != "bearing.schema.json"]


def test_the_schema_is_a_valid_draft_2020_12_schema():
    jsonschema.Draft202012Validator.check_schema(SCHEMA)


@pytest.mark.parametrize("path", BEARINGS, ids=lambda p: p.name)
def test_every_bearing_file_validates(path):
    jsonschema.Draft202012Validator(SCHEMA).validate(json.loads(path.read_text()))


def test_a_catalogue_block_alone_validates():
    jsonschema.Draft202012Validator(SCHEMA).validate(
        {
            "$schema": "bearing.schema.json",
            "name": "30206",
            "kind": "tapered",
            "catalogue": {"d_mm": 30, "D_mm": 62, "T_mm": 17.25, "Cr_N": 43000, "e": 0.37},
        }
    )


@pytest.mark.parametrize(
    "mutate",
    [
        lambda b: b["rollers"].update({"lenght_mm": 3.0}),
        lambda b: b["rollers"].update({"count": "seventeen"}),
        lambda b: b.update({"contact_law": "hertz"}),
        lambda b: b.pop("name"),
        lambda b: b.update({"catalogue": {"d_mm": 30}}),
    ],
    ids=["misspelt key", "wrong type", "unknown law", "no name", "catalogue without C_r"],
)
def test_what_the_reader_refuses_fails_the_schema(mutate):
    bearing = json.loads((REPO / "presets" / "TRB130x230.json").read_text())
    mutate(bearing)
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.Draft202012Validator(SCHEMA).validate(bearing)
