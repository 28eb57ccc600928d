"""Ordered expressions (simulation/ordered_expressions.py) evaluate to the same floats as
the Python formulas they are written from."""

import numpy as np

from tegrasp_drake.robotiq import linkage
from tegrasp_drake.simulation.ordered_expressions import SYMBOLIC, variable_of, variables


def test_ordered_expressions_evaluate_in_pythons_float_order():
    # Sums of three, products of four, a square and like terms: pydrake.symbolic's own
    # canonical forms round these differently from Python (x + 0.5 c h h, 2 a + 3 a).
    formulas = [lambda a, b, c, h: a + b * h + 0.5 * c * h * h,
                lambda a, b, c, h: 2.0 * a + 3.0 * a + a * a,
                lambda a, b, c, h: (a + 1.0) - 1.0 + (0.1 + 0.2) * b,
                lambda a, b, c, h: a * b * c * h - (a - b) / (c + 1e-3 * h)]
    symbols = variables("abch")
    expressions = [formula(*symbols).expression for formula in formulas]
    rng = np.random.default_rng(3)
    for _ in range(3000):
        values = (rng.normal(size=4) * 10.0 ** rng.integers(-6, 6, size=4)).tolist()
        environment = dict(zip(map(variable_of, symbols), values))
        for formula, expression in zip(formulas, expressions):
            assert expression.Evaluate(environment) == formula(*values)


def test_the_linkage_functions_write_the_same_formula_symbolically():
    (x,) = variables("x")
    functions = {name: getattr(linkage, name)(x, SYMBOLIC).expression
                 for name in ("half_opening", "driver_angle", "half_opening_rate")}
    for value in np.linspace(-0.05, 0.9, 400).tolist():
        for name, expression in functions.items():
            assert expression.Evaluate({variable_of(x): value}) == \
                getattr(linkage, name)(value), name
