"""Symbolic expressions that a compiled system evaluates as Python evaluates the same formula
on floats: the same IEEE operations on the same operands, in the same order.

pydrake.symbolic's canonical forms (n-ary sums, merged terms, folded constants, x * x as
pow) round differently; where it does not keep a binary operation as one node, `Ordered`
wraps the operands in max(operand, -inf), which no sum or product looks into."""

import math

from pydrake.symbolic import Expression, ExpressionKind, Formula, Variable
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
    if expression.get_kind() in (ExpressionKind.Var, ExpressionKind.Constant):
        return expression
    return symbolic_max(expression, -math.inf)


def _same(a: Expression, b: Expression) -> bool:
    return a.EqualTo(b)


def _constant(e: Expression):
    return e.Evaluate() if e.get_kind() == ExpressionKind.Constant else None


def _kept_sum(result: Expression, left: Expression, right: Expression) -> bool:
    """Whether `result` (left + right) is one sum node of exactly those two operands."""
    if result.get_kind() != ExpressionKind.Add:
        return False
    _, (constant, *terms) = result.Unapply()
    left_constant, right_constant = _constant(left), _constant(right)
    if len(terms) == 2 and constant == 0.0:
        return ((_same(terms[0], left) and _same(terms[1], right))
                or (_same(terms[0], right) and _same(terms[1], left)))
    if len(terms) == 1:
        return ((left_constant == constant and _same(terms[0], right))
                or (right_constant == constant and _same(terms[0], left)))
    return False


def _kept_product(result: Expression, left: Expression, right: Expression) -> bool:
    """Whether `result` (left * right) is one product node of exactly those two factors."""
    if result.get_kind() != ExpressionKind.Mul:
        return False
    _, (constant, *factors) = result.Unapply()
    if len(factors) == 2 and constant == 1.0:
        return ((_same(factors[0], left) and _same(factors[1], right))
                or (_same(factors[0], right) and _same(factors[1], left)))
    if len(factors) == 1:
        return ((_constant(left) == constant and _same(factors[0], right))
                or (_constant(right) == constant and _same(factors[0], left)))
    return False


def _build(operation, left: Expression, right: Expression) -> Expression:
    """operation(left, right) as one node, on opaque operands if pydrake would merge it."""
    result = operation(left, right)
    if operation is _divide:
        kept = (result.get_kind() == ExpressionKind.Div
                and all(map(_same, result.Unapply()[1], (left, right))))
    elif operation is _multiply:
        kept = _kept_product(result, left, right)
    else:
        kept = _kept_sum(result, left, -right if operation is _subtract else right)
    if kept:
        return result
    left, right = _opaque(left), _opaque(right)
    if operation is _multiply and left.EqualTo(right):
        right = symbolic_max(right, -math.inf)  # x * x, not pow(x, 2)
    return operation(left, right)


class Ordered:
    """A symbolic value whose +, -, *, / keep Python's order; comparisons give Formulas."""

    __slots__ = ("expression",)

    def __init__(self, value):
        self.expression = _expression(value)

    def _binary(self, other, operation, reverse: bool = False) -> "Ordered":
        left, right = _expression(self), _expression(other)
        if reverse:
            left, right = right, left
        return Ordered(_build(operation, left, right))

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
    """One Ordered symbolic variable per name, in order."""
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


# robotiq/linkage.py's Functions on Ordered values
SYMBOLIC = Functions(cos=cos, sin=sin, acos=acos, min=ordered_min, max=ordered_max,
                     number=Ordered)
