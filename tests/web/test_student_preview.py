"""The live preview reads an answer exactly as the checker will, and never compares it with anything."""

from grader.web.student.preview import allowed_names, expected_dimension, preview

TENSION = {"name": "tension", "kind": "expression", "reference": "g*m/3", "dimension": "kg*m*s^-2",
           "variables": {"g": {"dimension": "m*s^-2", "domain": "positive"},
                         "m": {"dimension": "kg", "domain": "positive"}}}


def test_implicit_products_are_read_and_explained():
    result = preview(TENSION, "mg/3")
    assert result["ok"] and result["latex"] == r"\frac{g m}{3}"
    assert "read 'mg' as m·g" in result["notes"]
    assert result["dimension"] == "a force (kg·m/s²)" and result["warning"] is None


def test_a_typo_is_an_error_with_its_position_and_a_hint():
    result = preview(TENSION, "m*g*sin(thta)")
    assert not result["ok"]
    assert result["error"]["position"] == 8 and result["error"]["code"] == "unknown_name"


def test_a_wrong_dimension_is_a_warning_not_an_error():
    result = preview(TENSION, "m")
    assert result["ok"] and "should be a force" in result["warning"]


def test_empty_and_overlong_texts_say_so():
    assert preview(TENSION, "  ")["error"]["code"] == "empty"
    assert preview(TENSION, "m+" * 3000)["error"]["code"] == "too_long"


def test_the_preview_never_carries_the_reference():
    assert "g*m/3" not in str(preview(TENSION, "m*g"))


def test_the_names_and_dimension_a_student_may_know():
    assert [n["name"] for n in allowed_names(TENSION)] == ["g", "m"]
    assert expected_dimension(TENSION) == "a force (kg·m/s²)"


NUMERIC = {**TENSION, "name": "tension_value", "kind": "numeric", "unit": "N"}


def test_a_numeric_answer_is_read_as_a_number_with_its_unit():
    result = preview(NUMERIC, "1.47e1 kN")
    assert result["ok"] and result["latex"] == r"14.7\,\mathrm{kN}" and result["warning"] is None
    assert result["dimension"] == "a force (kg·m/s²)"


def test_a_numeric_answer_warns_of_a_missing_or_wrong_unit_and_refuses_a_decimal_comma():
    assert preview(NUMERIC, "14.7")["warning"] == "Give a unit: the answer is a force (kg·m/s²)."
    assert "The unit m/s is a velocity" in preview(NUMERIC, "14.7 m/s")["warning"]
    comma = preview(NUMERIC, "14,7 N")
    assert not comma["ok"] and "14.7, not 14,7" in comma["error"]["message"]
