"""Symbolic expressions that a compiled system evaluates as Python evaluates the same
formula on floats: the same IEEE operations on the same operands, in the same order.

pydrake.symbolic keeps an expression in a canonical form: a sum is one node of all its
terms (x + y + z, in the node's own order), a product one node of its factors (and x * x
becomes pow(x, 2)), like terms merge (2 x + 3 x = 5 x). Evaluated, such a node rounds
differently from Python's left-to-right (x + y) + z. `Ordered` wraps each result of a
binary operation in an opaque node, max(result, -inf), which equals the result (NaN
included) and which no later sum or product looks into: every sum and product node then has
two operands, whose order does not change the rounding (IEEE addition and multiplication
commute), and a squared operand stays a product. Subtraction is a sum with a -1 coefficient
and negation a product with -1, both exact.

Write the formula as Python would evaluate it (operator precedence and left-to-right order
are Python's: `a + b * c` is a + (b * c)); compare a system built this way with the Python
function on floats bit for bit in its tests (floating-point signed zeros aside: 0.0 + x is
how a sum node starts, so a -0.0 result may come out +0.0).
"""

import math

from pydrake.symbolic import Expression, Formula, Variable
from pydrake.symbolic import abs as symbolic_abs
from pydrake.symbolic import acos as symbolic_acos
from pydrake.symbolic import cos as symbolic_cos
from pydrake.symbolic import if_then_else
from pydrake.symbolic import max as symbolic_max
from pydrake.symbolic import min as symbolic_min
from pydrake.symbolic import sin as symbolic_sin

from tegrasp_drake.robotiq.linkage import Functions


def _expression(value) -> Expression:
    if isinstance(value, Ordered):
        return value.expression
    return value if isinstance(value, Expression) else Expression(value)


def _opaque(expression: Expression) -> Expression:
    """The expression as one node that sums and products do not merge into."""
    return symbolic_max(expression, -math.inf)


class Ordered:
    """A symbolic value whose +, -, *, / keep Python's floating-point order (module
    docstring); comparisons give Formulas (for `where`)."""

    __slots__ = ("expression",)

    def __init__(self, value):
        self.expression = _expression(value)

    def _binary(self, other, operation, reverse: bool = False) -> "Ordered":
        left, right = _expression(self), _expression(other)
        if reverse:
            left, right = right, left
        if operation is _multiply and left.EqualTo(right):
            right = _opaque(right)  # x * x, not pow(x, 2)
        return Ordered(_opaque(operation(left, right)))

    def __add__(self, other):
        return self._binary(other, _add)

    def __radd__(self, other):
        return self._binary(other, _add, reverse=True)

    def __sub__(self, other):
        return self._binary(other, _subtract)

    def __rsub__(self, other):
        return self._binary(other, _subtract, reverse=True)

    def __mul__(self, other):
        return self._binary(other, _multiply)

    def __rmul__(self, other):
        return self._binary(other, _multiply, reverse=True)

    def __truediv__(self, other):
        return self._binary(other, _divide)

    def __rtruediv__(self, other):
        return self._binary(other, _divide, reverse=True)

    def __neg__(self):
        return Ordered(-self.expression)

    def __abs__(self):
        return Ordered(symbolic_abs(self.expression))

    def __lt__(self, other) -> Formula:
        return self.expression < _expression(other)

    def __le__(self, other) -> Formula:
        return self.expression <= _expression(other)

    def __gt__(self, other) -> Formula:
        return self.expression > _expression(other)

    def __ge__(self, other) -> Formula:
        return self.expression >= _expression(other)

    def equals(self, other) -> Formula:
        """The Formula self == other (== itself is left to Python's identity)."""
        return self.expression == _expression(other)

    def differs(self, other) -> Formula:
        return self.expression != _expression(other)


def _add(a, b):
    return a + b


def _subtract(a, b):
    return a - b


def _multiply(a, b):
    return a * b


def _divide(a, b):
    return a / b


def variables(names) -> list[Ordered]:
    """One Ordered symbolic variable per name (the system's inputs), in order; the
    Variables themselves are `.expression.GetVariables()` of each, or `variable_of`."""
    return [Ordered(Variable(name)) for name in names]


def variable_of(value: Ordered) -> Variable:
    """The Variable an Ordered made by `variables` stands for."""
    (variable,) = value.expression.GetVariables()
    return variable


def where(condition: Formula, then, otherwise) -> Ordered:
    """`then` if condition else `otherwise` (evaluates only the branch taken)."""
    return Ordered(if_then_else(condition, _expression(then), _expression(otherwise)))


def ordered_min(a, b) -> Ordered:
    """Python's min(a, b): a unless b < a."""
    return Ordered(symbolic_min(_expression(a), _expression(b)))


def ordered_max(a, b) -> Ordered:
    """Python's max(a, b): a unless b > a."""
    return Ordered(symbolic_max(_expression(a), _expression(b)))


def sin(a) -> Ordered:
    return Ordered(symbolic_sin(_expression(a)))


def cos(a) -> Ordered:
    return Ordered(symbolic_cos(_expression(a)))


def acos(a) -> Ordered:
    return Ordered(symbolic_acos(_expression(a)))


def expressions(values) -> list[Expression]:
    """The Expressions of Ordered values (or numbers), for a SymbolicVectorSystem."""
    return [_expression(value) for value in values]


# The closed-form linkage's functions on Ordered values (robotiq/linkage.py Functions).
SYMBOLIC = Functions(cos=cos, sin=sin, acos=acos, min=ordered_min, max=ordered_max,
                     number=Ordered)
