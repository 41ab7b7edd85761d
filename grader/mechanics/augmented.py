"""The augmented system [M Jᵀ; J 0] of constrained motion: when it is solvable, and its solution.

The Euler–Lagrange rows and the twice-differentiated constraints are linear in (q̈, λ):

    M q̈ + C λ = b₁,   J q̈ = b₂        (C = −Jᵀ with the paper's L' = L + Σ λ f).

The mass matrix M may be singular (a winding angle, a massless pulley or link: a coordinate with
no kinetic energy of its own); the motion is still determined whenever the whole augmented matrix
is nonsingular, i.e. whenever M is positive on the directions the constraints allow. Only a truly
singular augmented matrix is refused, naming the coordinates or constraints along its null space.

The system is solved exactly over the polynomials in its symbols (and in the sines and cosines
it contains, as generators) with sympy's ``DomainMatrix``, fraction-free (Bareiss): x = adj/det
with exact divisions only, then each entry cancelled by the irreducible factors of det, which is
what a gcd would remove. LU over the field of rational functions cancels a gcd at every step
instead: fine for a pendulum, but its multivariate gcds grow with the symbols and the loops of
a closed chain (a swing seat on two parallel ropes: 110 s, against 1 s fraction-free). Solving
with LU on sympy expressions and cancelling afterwards takes a double pendulum in Cartesian
coordinates from 0.05 s to seconds or minutes.

Examples
--------
A bead on a massless rod of angle φ tied to its position x by x = R φ: M = diag(m, 0) is
singular, the augmented matrix is not.

>>> import sympy
>>> m, g, R = sympy.symbols("m g R", positive=True)
>>> A = sympy.Matrix([[m, 0, -1], [0, 0, R], [1, -R, 0]])
>>> b = sympy.Matrix([m*g, 0, 0])
>>> solve_augmented(A, b, 2)
[g, g/R, 0]
>>> singular_directions(sympy.Matrix([[m, 0], [0, 0]]), 2, ["x", "phi"], [])
'the coordinate phi has no kinetic energy of its own and no constraint ties it to the others'
"""

from __future__ import annotations

import numpy
import sympy
from sympy.polys.matrices import DomainMatrix

__all__ = ["generic_point", "singular_directions", "solve_augmented"]


def generic_point(symbols) -> dict:
    """A reproducible 'generic' point: irrational-looking values where no identity holds by accident.

    >>> x, y = sympy.symbols("x y")
    >>> generic_point({x, y})
    {x: 3/2, y: 391/291}
    """
    primes = [2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53, 59, 61, 67, 71, 73, 79, 83, 89]
    point = {}
    for i, s in enumerate(sorted(symbols, key=str)):
        p = primes[i % len(primes)]
        point[s] = sympy.Rational(p + 1, p) + sympy.Rational(i, 97)
    return point


def singular_directions(A: sympy.Matrix, n: int, coordinates: list[str], constraints: list[str]) -> str | None:
    """None when the augmented matrix is nonsingular at a generic point, else what makes it singular.

    ``A`` is the (n + k) × (n + k) augmented matrix, ``coordinates`` and ``constraints`` the names
    of its first n and last k unknowns. The message names the coordinates (and multipliers) that
    carry the null space, so an instructor knows where energy or a constraint is missing.
    """
    numeric = numpy.array(A.subs(generic_point(A.free_symbols)).evalf(), dtype=float)
    if numeric.size == 0:
        return None
    _, sigma, vt = numpy.linalg.svd(numeric)
    tolerance = 1e-10 * max(1.0, sigma[0])
    if sigma[-1] > tolerance:
        return None
    null = vt[-1]
    big = abs(null) > 1e-6 * abs(null).max()
    free = [coordinates[i] for i in range(n) if big[i]]
    multipliers = [constraints[i - n] for i in range(n, len(null)) if big[i]]
    if multipliers and not free:
        return (f"the constraints ({', '.join(multipliers)}) are redundant or singular: their gradients "
                "with respect to the coordinates are linearly dependent")
    if len(free) == 1:
        return (f"the coordinate {free[0]} has no kinetic energy of its own and no constraint ties it "
                "to the others")
    return (f"the coordinates {', '.join(free)} can move together without kinetic energy "
            "(the mass matrix is singular along a direction the constraints allow)")


def solve_augmented(A: sympy.Matrix, b: sympy.Matrix, n: int | None = None) -> list[sympy.Expr]:
    """Solve A x = b exactly, each component one cancelled fraction (see the module notes).

    ``n`` (the number of coordinates) is accepted for symmetry with :func:`singular_directions`;
    the solve itself does not need the block structure.

    Sines, cosines and roots enter as generators of their own (:func:`_generators`): sympy builds
    no polynomial domain over sin α and cos α together (they are algebraically dependent), and
    would fall back to expressions, ten times slower on a disk rolling down a sliding wedge.

    >>> a, m = sympy.symbols("alpha m", positive=True)
    >>> solve_augmented(sympy.Matrix([[m, sympy.sin(a)], [sympy.sin(a), -sympy.cos(a)]]), sympy.Matrix([m, 0]))
    [m*cos(alpha)/(m*cos(alpha) + sin(alpha)**2), m*sin(alpha)/(m*cos(alpha) + sin(alpha)**2)]
    """
    generators = _generators(A, b)
    back = {d: e for e, d in generators.items()}
    try:
        dA, dB = DomainMatrix.from_Matrix(A.xreplace(generators)).unify(
            DomainMatrix.from_Matrix(b.xreplace(generators)))
        if dA.domain.is_EX:
            raise _NotPolynomial
        solution = _fraction_free_solve(dA, dB)
        memo: dict = {}  # the solution's entries mostly share one denominator (the determinant)
        solution = solution.applyfunc(lambda e: _pythagorean(e, generators, memo)).xreplace(back)
    except (_NotPolynomial, NotImplementedError, ZeroDivisionError):
        # Entries that are still not polynomials in their generators: sympy's own LU on
        # expressions, slower but general.
        solution = A.LUsolve(b).applyfunc(sympy.cancel)
    return list(solution)


def _fraction_free_solve(dA: DomainMatrix, dB: DomainMatrix) -> sympy.Matrix:
    """x = A⁻¹B over polynomials, each entry one cancelled fraction, as LU over the field gives it.

    Bareiss's elimination gives x = N/det with exact divisions only. gcd(Nᵢ, det) is a product of
    det's irreducible factors, so dividing Nᵢ and det by each factor while it divides (a remainder
    test, no gcd) cancels the fraction; ``cancel`` then only has coprime polynomials left to put in
    the field's canonical form (integer content and sign). Rows with fractions in them (1/R) are
    first multiplied by their denominators' lcm, which leaves the solution as it is.
    """
    if dA.domain.is_FractionField:
        dA, dB = _cleared_rows(dA, dB)
    elif not dA.domain.is_PolynomialRing:  # numbers (ZZ, QQ): nothing to cancel
        return dA.to_field().lu_solve(dB.to_field()).to_Matrix()
    ring = dA.domain
    numerators, determinant = dA.solve_den(dB)
    _, factors = determinant.factor_list()
    entries = []
    for row in numerators.to_list():
        cancelled = []
        for numerator in row:
            denominator = determinant
            for factor, multiplicity in factors:
                for _ in range(multiplicity):
                    quotient, remainder = divmod(numerator, factor)
                    if remainder:
                        break
                    numerator, denominator = quotient, denominator.exquo(factor)
            numerator, denominator = numerator.cancel(denominator)
            cancelled.append(ring.to_sympy(numerator) / ring.to_sympy(denominator))
        entries.append(cancelled)
    return sympy.Matrix(entries)


def _cleared_rows(dA: DomainMatrix, dB: DomainMatrix) -> tuple[DomainMatrix, DomainMatrix]:
    """[A | B] over rational functions, each row times its denominators' lcm: over polynomials."""
    field = dA.domain
    ring = field.get_ring()
    a, b = dA.to_list(), dB.to_list()
    for i in range(len(a)):
        lcm = ring.one
        for entry in a[i] + b[i]:
            lcm = lcm.lcm(entry.denom)
        a[i] = [ring(entry.numer * lcm.exquo(entry.denom)) for entry in a[i]]
        b[i] = [ring(entry.numer * lcm.exquo(entry.denom)) for entry in b[i]]
    return DomainMatrix(a, dA.shape, ring), DomainMatrix(b, dB.shape, ring)


def _pythagorean(value: sympy.Expr, generators: dict[sympy.Expr, sympy.Dummy],
                 memo: dict | None = None) -> sympy.Expr:
    """A solved fraction with sin² + cos² = 1 used in its denominator where it shortens it.

    The generators sin u and cos u are independent symbols to the solve, so a slot turning at ω
    leaves m (x² + y²)(sin²ωt + cos²ωt) in a denominator. The denominator is reduced modulo
    s² + c² − 1 (as a polynomial in c, then in s) and the shorter form kept. Only the denominator,
    and no new cancellation: the numerators of a top on a pivot are hundreds of terms long, and
    reducing and cancelling those took seconds for nothing a reader sees. ``memo`` remembers
    each denominator's reduction (the entries of one solution mostly share theirs).
    """
    pairs = [(generators[sympy.sin(f.args[0])], d) for f, d in generators.items()
             if isinstance(f, sympy.cos) and sympy.sin(f.args[0]) in generators]
    if not pairs or value == 0:
        return value
    numerator, denominator = sympy.fraction(value)
    if memo is not None and denominator in memo:
        best = memo[denominator]
        return value if best == denominator else numerator / best
    best = denominator
    for s, c in pairs:
        if not ({s, c} <= best.free_symbols):
            continue
        identity = s ** 2 + c ** 2 - 1
        for square in (c, s):
            reduced = sympy.factor_terms(sympy.rem(sympy.expand(best), identity, square))
            if sympy.count_ops(reduced) < sympy.count_ops(best):
                best = reduced
    if memo is not None:
        memo[denominator] = best
    return value if best is denominator else numerator / best


def _generators(*matrices: sympy.Matrix) -> dict[sympy.Expr, sympy.Dummy]:
    """A symbol for each function value (sin α, cos ωt) and fractional power (√(x² + y²)) in the matrices.

    Outermost first, so that sin(√x) is one generator; a rational function in these symbols is
    what ``DomainMatrix`` solves over fast.
    """
    found: dict[sympy.Expr, sympy.Dummy] = {}

    def visit(expr: sympy.Expr) -> None:
        if isinstance(expr, sympy.Function) or (expr.is_Pow and not expr.exp.is_Integer):
            if expr not in found:
                found[expr] = sympy.Dummy("g")
            return
        for arg in expr.args:
            visit(arg)

    for matrix in matrices:
        for entry in matrix:
            visit(entry)
    return found


class _NotPolynomial(Exception):
    pass
