"""Who may do what: the one access policy of the API, the pages, the CSV exports and the LMS.

Every view asks this module; no view decides access on its own. Two layers:

- a coarse role check at the door (``roles=`` of an API route, ``login_required`` of a page) says
  which *kind* of account may call an endpoint at all;
- :func:`allowed` decides about one *resource* (a problem, a version, a submission), from a
  :class:`Principal`: who is asking, as which role, and the courses they take or teach.

The rules (an admin may do everything; an anonymous caller nothing):

=====================  =====================================================================
action                 who, besides admins
=====================  =====================================================================
``see``                a problem's statement: everyone who manages it (drafts too); anyone
                       else only a *published* version, and only of a problem in no course or
                       in a course they are enrolled in (as student or instructor). An LMS is
                       "enrolled" in the courses its account is linked to by an Enrolment.
                       A problem held by an assignment that has not opened is hidden from the
                       students of its course until it opens (`find_version`, `visible_versions`),
                       as the assignment's page hides its statement.
``submit``             the same as ``see``: whoever sees a version may answer it. An *archived*
                       problem is seen by its managers only, and answered by nobody.
``submit_for_others``  an LMS for a published problem it sees (its linked courses or no course);
                       an instructor for a problem they manage. A student only ever for itself.
                       For one student (`may_act_for`): an LMS only for a student who may
                       answer the version themselves and is enrolled in a course linked to it
                       (an LMS linked to one course enrols there a student it names for the
                       first time); an instructor for a student of a course they teach.
``manage``             instructors, for problems of courses they teach (``Enrolment.role ==
                       "instructor"``) and problems in no course: read references and drafts,
                       list its versions, publish and unpublish one, upload or edit a new
                       version over the problem's id, archive the problem and restore it
                       (archived, it stays theirs to manage). The same on the pages and the API.
``read_grades``        those who manage the problem; an LMS for published problems of its
                       linked courses (grade passback), never for problems in no course.
``regrade``            those who manage the problem.
``export``             those who manage the problem (CSV of grades or submissions).
``view_submission``    its student; the LMS that sent it; instructors who manage its problem.
                       On a problem in no course (shared), an instructor sees, there and in
                       grades and exports, only the work of students of the courses they teach
                       or assist and of students in no course (`students_in_view`). A hand-in
                       for an assignment is its course's business: besides its student (and
                       the LMS that sent it), only that course's instructors and TAs see it,
                       never another course's instructor through a shared problem.
``view_derivation``    an uploaded scene's derivation job: the instructor who uploaded it, and
                       the instructors who teach its course (the course chosen at upload, or
                       the course of the problem it made).
``create``             (no resource) instructors: upload a scene under a new id.
``create_course``      (no resource) instructors: start a course (they teach it).
``view_course``        a Course or Assignment: everyone enrolled in the course (any role, an
                       LMS linked to it): its page, its assignments, one's own scores.
``grade_course``       its instructors and teaching assistants (``Enrolment.role == "ta"``):
                       roster, gradebook, everyone's submissions of its assignments.
``manage_course``      its instructors: enrol people, build assignments, release solutions.
                       TAs grade but never publish: they have neither this nor ``manage``.
``check``              (no resource) any authenticated caller: the stateless ``POST /check``.
=====================  =====================================================================

Refusals are the same on every surface: a caller who may not even *see* a resource gets 404, as if
it did not exist (a student cannot learn that a draft or another student's attempt exists); a
caller who may see it but not do this gets 403. Under ``/api/`` both are problem documents.

Examples
--------
>>> from grader.store.models import Problem, ProblemVersion
>>> draft = ProblemVersion(published=False, problem=Problem(slug="mech", course_id=1))
>>> teacher = Principal(user_id=7, role="instructor", taught=frozenset({1}), enrolled=frozenset({1}))
>>> student = Principal(user_id=8, role="student", enrolled=frozenset({1}))
>>> allowed(teacher, Action.SEE, draft), allowed(student, Action.SEE, draft)
(True, False)
>>> draft.published = True
>>> allowed(student, Action.SUBMIT, draft), allowed(student, Action.READ_GRADES, draft)
(True, False)
"""

from __future__ import annotations

import enum
from dataclasses import dataclass
from datetime import datetime, timezone
from typing import NoReturn, Union

from flask import abort, g, has_app_context
from sqlalchemy import and_, func, select
from sqlalchemy.orm import Session, selectinload

from grader.store.db import db
from grader.store.models import (Assignment, Course, DerivationJob, Enrolment, Problem, ProblemVersion, Submission,
                                 User)
from grader.store.assignments import unopened_problems
from grader.store.problems import latest_version, problem_by_slug
from grader.web import clock
from grader.web.errors import ApiProblem, wants_problem_json

__all__ = [
    "API_ROLES",
    "INSTRUCTOR_ROLES",
    "PAGE_ROLES",
    "STUDENT_ROLES",
    "Action",
    "Principal",
    "allowed",
    "current_principal",
    "find_assignment",
    "find_course",
    "find_derivation",
    "find_problem",
    "may_act_for",
    "students_in_view",
    "find_problem_version",
    "find_submission",
    "find_version",
    "managed_courses",
    "managed_problems",
    "may_update",
    "my_courses",
    "require",
    "require_upload",
    "visible_versions",
]


class Action(str, enum.Enum):
    """What a principal wants to do with a resource (see the module's table)."""

    SEE = "see"
    SUBMIT = "submit"
    SUBMIT_FOR_OTHERS = "submit_for_others"
    MANAGE = "manage"
    READ_GRADES = "read_grades"
    REGRADE = "regrade"
    EXPORT = "export"
    VIEW_SUBMISSION = "view_submission"
    VIEW_DERIVATION = "view_derivation"
    CREATE = "create"
    CHECK = "check"
    CREATE_COURSE = "create_course"
    VIEW_COURSE = "view_course"
    GRADE_COURSE = "grade_course"
    MANAGE_COURSE = "manage_course"


Resource = Union[Problem, ProblemVersion, Submission, DerivationJob, Course, Assignment, None]

# The doors: which roles may call a kind of endpoint at all (``spec.route(roles=...)``,
# ``login_required(...)``), before any resource is looked at.
STUDENT_ROLES = frozenset({"student"})
INSTRUCTOR_ROLES = frozenset({"instructor", "admin"})
PAGE_ROLES = frozenset({"student", "instructor", "admin"})  # an "lms" account only uses the API
API_ROLES = frozenset({"student", "instructor", "admin", "lms"})
_ROLE_ONLY = {Action.CREATE: INSTRUCTOR_ROLES, Action.CHECK: API_ROLES, Action.CREATE_COURSE: INSTRUCTOR_ROLES}
_COURSE_ACTIONS = (Action.VIEW_COURSE, Action.GRADE_COURSE, Action.MANAGE_COURSE)


@dataclass(frozen=True)
class Principal:
    """Who is asking: a user acting in a role (a page session's role or an API token's role).

    ``enrolled`` holds every course the user is enrolled in, in any role; ``taught`` the courses
    they are an instructor of; ``assisted`` those they are a teaching assistant of. An anonymous
    caller has ``role`` None and may do nothing.
    """

    user_id: int | None = None
    role: str | None = None
    enrolled: frozenset[int] = frozenset()
    taught: frozenset[int] = frozenset()
    assisted: frozenset[int] = frozenset()

    @classmethod
    def of(cls, session: Session, user: User | None, role: str | None = None) -> Principal:
        """The principal of ``user`` acting as ``role`` (default: the user's own role)."""
        if user is None:
            return ANONYMOUS
        rows = session.execute(select(Enrolment.course_id, Enrolment.role).where(Enrolment.user_id == user.id)).all()
        return cls(user_id=user.id, role=role or user.role, enrolled=frozenset(c for c, _ in rows),
                   taught=frozenset(c for c, r in rows if r == "instructor"),
                   assisted=frozenset(c for c, r in rows if r == "ta"))

    @property
    def is_admin(self) -> bool:
        return self.role == "admin"

    def manages_course(self, course_id: int | None) -> bool:
        """Whether this principal manages problems of ``course_id`` (None: problems in no course)."""
        if self.is_admin:
            return True
        return self.role == "instructor" and (course_id is None or course_id in self.taught)

    def in_scope(self, course_id: int | None) -> bool:
        """Whether published problems of ``course_id`` are open to this principal."""
        return self.role is not None and (course_id is None or course_id in self.enrolled)


ANONYMOUS = Principal()


def _problem(resource: Problem | ProblemVersion) -> Problem:
    return resource.problem if isinstance(resource, ProblemVersion) else resource


def _published(resource: Problem | ProblemVersion) -> bool:
    if isinstance(resource, ProblemVersion):
        return bool(resource.published)
    return any(v.published for v in resource.versions)


def _archived(resource: Resource) -> bool:
    return isinstance(resource, (Problem, ProblemVersion)) and _problem(resource).archived_at is not None


def allowed(principal: Principal, action: Action, resource: Resource = None) -> bool:
    """Whether ``principal`` may do ``action`` to ``resource`` (a problem, a version or a submission).

    For a :class:`~grader.store.models.Problem`, "published" means "has a published version"; for a
    :class:`~grader.store.models.ProblemVersion`, that version itself.
    """
    action = Action(action)
    if principal.role is None:
        return False
    if action in _ROLE_ONLY:
        return principal.role in _ROLE_ONLY[action]
    if resource is None:
        return False
    if action in (Action.SUBMIT, Action.SUBMIT_FOR_OTHERS) and _archived(resource):
        return False  # kept for the record; nobody answers it any more, admins neither
    if principal.is_admin:
        return True
    if isinstance(resource, (Course, Assignment)):
        return _may_course(principal, action, resource.id if isinstance(resource, Course) else resource.course_id)
    if action in _COURSE_ACTIONS:
        return False
    if isinstance(resource, Submission):
        return action is Action.VIEW_SUBMISSION and _may_view_submission(principal, resource)
    if isinstance(resource, DerivationJob):
        return action is Action.VIEW_DERIVATION and _may_view_derivation(principal, resource)
    if action in (Action.VIEW_SUBMISSION, Action.VIEW_DERIVATION):
        return False
    course = _problem(resource).course_id
    manages = principal.manages_course(course)
    if action in (Action.MANAGE, Action.REGRADE, Action.EXPORT):
        return manages
    open_to_me = manages or (_published(resource) and not _archived(resource) and principal.in_scope(course))
    if action in (Action.SEE, Action.SUBMIT):
        return open_to_me
    if action is Action.SUBMIT_FOR_OTHERS:
        return manages or (principal.role == "lms" and open_to_me)
    if action is Action.READ_GRADES:
        # An LMS reads grades only of its own (linked) courses: a problem in no course is open to
        # every student of every LMS, and its grades are none of one LMS's business.
        return manages or (principal.role == "lms" and course is not None and open_to_me)
    return False


def may_act_for(principal: Principal, student: Principal, version: ProblemVersion) -> bool:
    """Whether ``principal`` may submit ``version`` for ``student`` (``submit_for_others``, for this one).

    The student must be one of the caller's: enrolled in a course the LMS is linked to (and able to
    answer the version themselves), or in a course the instructor teaches. Without it, an LMS of one
    course acted (and read the results) for the students of every other course.

    Examples
    --------
    >>> from grader.store.models import Problem, ProblemVersion
    >>> shared = ProblemVersion(published=True, problem=Problem(slug="yoyo", course_id=None))
    >>> moodle = Principal(user_id=1, role="lms", enrolled=frozenset({1}))
    >>> ours, theirs = (Principal(user_id=n, role="student", enrolled=frozenset({c})) for n, c in ((2, 1), (3, 2)))
    >>> may_act_for(moodle, ours, shared), may_act_for(moodle, theirs, shared)
    (True, False)
    """
    if not (allowed(principal, Action.SUBMIT_FOR_OTHERS, version) and student.role == "student"):
        return False
    if principal.is_admin:
        return True
    if principal.role == "lms":
        return allowed(student, Action.SUBMIT, version) and bool(principal.enrolled & student.enrolled)
    return bool(principal.taught & student.enrolled)  # an instructor of the problem tries a draft for them too


def students_in_view(principal: Principal, course_id: int | None):
    """Whose work on a problem of ``course_id`` a caller who may read its grades sees, as a condition
    on a submission's user-id and assignment-id columns, ``condition(user_id, assignment_id)``, or None
    for everyone's.

    A problem of a course: everyone's (its students'). A problem in no course is shared by every
    instructor, and by students of every course: each instructor sees the students of the courses
    they teach or assist and the students in no course, never another course's (an instructor of
    OTHER read MECH's names and scores through a shared problem); and of their hand-ins, only those
    for the assignments of those courses (an instructor of OTHER who enrolled a student of MECH read
    her hand-ins for MECH's homework). Admins see everyone's.
    """
    if course_id is not None or principal.is_admin or principal.role == "lms":
        return None
    mine = principal.taught | principal.assisted

    def condition(user_id, assignment_id):
        a_student_somewhere = select(Enrolment.id).where(Enrolment.user_id == user_id,
                                                         Enrolment.role == "student").exists()
        one_of_mine = select(Enrolment.id).where(Enrolment.user_id == user_id, Enrolment.course_id.in_(mine)).exists()
        my_assignments = select(Assignment.id).where(Assignment.course_id.in_(mine))
        return (~a_student_somewhere | one_of_mine) & (assignment_id.is_(None) | assignment_id.in_(my_assignments))

    return condition


def _sees_student(principal: Principal, course_id: int | None, student: User) -> bool:
    """`students_in_view` for one student already loaded."""
    if students_in_view(principal, course_id) is None:
        return True
    courses = {e.course_id for e in student.enrolments if e.role == "student"}
    return not courses or bool(courses & (principal.taught | principal.assisted))


def _may_course(principal: Principal, action: Action, course_id: int) -> bool:
    if action is Action.VIEW_COURSE:
        return course_id in principal.enrolled
    if action is Action.GRADE_COURSE:
        return principal.role != "lms" and course_id in (principal.taught | principal.assisted)
    if action is Action.MANAGE_COURSE:
        return principal.role == "instructor" and course_id in principal.taught
    return False


def _may_view_submission(principal: Principal, submission: Submission) -> bool:
    if submission.user_id == principal.user_id:
        return True
    if principal.role == "lms":
        return submission.requester_id == principal.user_id
    if submission.assignment_id is not None:
        # A hand-in is its course's business: its instructors and TAs grade it; nobody else does,
        # not even an instructor who manages its (shared) problem.
        return submission.assignment is not None and _may_course(
            principal, Action.GRADE_COURSE, submission.assignment.course_id)
    course_id = submission.problem_version.problem.course_id
    return (principal.role == "instructor" and principal.manages_course(course_id)
            and _sees_student(principal, course_id, submission.user))


def _may_view_derivation(principal: Principal, job: DerivationJob) -> bool:
    if job.requester_id == principal.user_id:
        return True
    made = job.problem_version.problem.course_id if job.problem_version is not None else None
    return principal.role == "instructor" and bool({job.course_id, made} & principal.taught)


def may_update(session: Session, user: User, problem: Problem) -> bool:
    """Whether ``user`` (in their own role) may add a version to the existing ``problem``.

    The rule the derivation workers are handed (``grader.jobs`` must not import the web layer).
    """
    return allowed(Principal.of(session, user), Action.MANAGE, problem)


# --- refusals: 404 hides what the caller may not see, 403 refuses what they may see ----------------

def _not_found(detail: str) -> NoReturn:
    if wants_problem_json():
        raise ApiProblem(404, detail, kind="not-found")
    abort(404, detail)


def _forbidden(detail: str) -> NoReturn:
    if wants_problem_json():
        raise ApiProblem(403, detail, kind="forbidden")
    abort(403, detail)


_SEEING = {Submission: Action.VIEW_SUBMISSION, Problem: Action.SEE, ProblemVersion: Action.SEE,
           DerivationJob: Action.VIEW_DERIVATION, Course: Action.VIEW_COURSE, Assignment: Action.VIEW_COURSE}


def _describe(resource: Resource) -> str:
    if isinstance(resource, Submission):
        return f"submission {resource.id}"
    if isinstance(resource, DerivationJob):
        return f"derivation {resource.id}"
    if isinstance(resource, Course):
        return f"course {resource.code!r}"
    if isinstance(resource, Assignment):
        return f"assignment {resource.slug!r}"
    if resource is None:
        return "resource"
    return f"problem {_problem(resource).slug!r}"


def require(principal: Principal, action: Action, resource: Resource) -> None:
    """Return if ``allowed``; else raise 404 if the caller may not even see ``resource``, 403 if they may."""
    if allowed(principal, action, resource):
        return
    if resource is not None and not allowed(principal, _SEEING[type(resource)], resource):
        _not_found(f"There is no {_describe(resource)}.")
    verb = Action(action).value.replace("_", " ")
    _forbidden(f"Your account may not {verb} this {_describe(resource).split(' ')[0]}.")


# --- lookups: the resource if the principal may act on it, else the refusal above ------------------

def find_problem(session: Session, principal: Principal, slug: str, action: Action = Action.SEE) -> Problem:
    """Problem ``slug`` if ``principal`` may ``action`` it; 404 if unknown, versionless or not visible."""
    problem = problem_by_slug(session, slug)
    if problem is None or not problem.versions:
        _not_found(f"There is no problem {slug!r}.")
    require(principal, action, problem)
    return problem


def find_problem_version(session: Session, principal: Principal, slug: str, number: int,
                         action: Action = Action.MANAGE) -> ProblemVersion:
    """Version ``number`` of problem ``slug`` if the principal may ``action`` the problem (404/403 as
    :func:`find_problem`); 404 if the problem has no such version."""
    problem = find_problem(session, principal, slug, action)
    version = next((v for v in problem.versions if v.number == number), None)
    if version is None:
        _not_found(f"Problem {slug!r} has no version {number}.")
    return version


def find_version(session: Session, principal: Principal, slug: str, action: Action = Action.SEE) -> ProblemVersion:
    """The version of ``slug`` the principal works with: the newest if they manage the problem (a
    draft, maybe), else the newest published one; 404/403 as :func:`require` says."""
    problem = problem_by_slug(session, slug)
    version = None
    if problem is not None:
        version = latest_version(session, problem, published_only=not allowed(principal, Action.MANAGE, problem))
    if version is None or (not allowed(principal, Action.MANAGE, problem)
                           and problem.id in _unopened(session, principal)):
        _not_found(f"There is no problem {slug!r}.")
    require(principal, action, version)
    return version


def _unopened(session: Session, principal: Principal) -> set[int]:
    """The problems a student may not see yet: held by an assignment of their course that has not opened."""
    if principal.role != "student" or principal.user_id is None:
        return set()
    now = clock.now() if has_app_context() else datetime.now(timezone.utc)  # the server's one clock
    return unopened_problems(session, principal.user_id, now)


def find_submission(session: Session, principal: Principal, submission_id: int) -> Submission:
    """Submission ``submission_id`` if the principal may view it, else 404 (never 403: not even its existence)."""
    submission = session.get(Submission, submission_id)
    if submission is None or not allowed(principal, Action.VIEW_SUBMISSION, submission):
        _not_found(f"There is no submission {submission_id}.")
    return submission


def find_derivation(session: Session, principal: Principal, job_id: int) -> DerivationJob:
    """Derivation job ``job_id`` if the principal may view it, else 404 (never 403)."""
    job = session.get(DerivationJob, job_id)
    if job is None or not allowed(principal, Action.VIEW_DERIVATION, job):
        _not_found(f"There is no derivation {job_id}.")
    return job


def find_course(session: Session, principal: Principal, code: str, action: Action = Action.VIEW_COURSE) -> Course:
    """Course ``code`` if the principal may ``action`` it; 404 if unknown or they are not in it, else 403."""
    course = session.scalar(select(Course).where(Course.code == code))
    if course is None:
        _not_found(f"There is no course {code!r}.")
    require(principal, action, course)
    return course


def find_assignment(session: Session, principal: Principal, code: str, slug: str,
                    action: Action = Action.VIEW_COURSE) -> Assignment:
    """Assignment ``slug`` of course ``code`` if the principal may ``action`` it (404/403 as :func:`require`)."""
    course = find_course(session, principal, code)
    assignment = session.scalar(select(Assignment).where(Assignment.course_id == course.id, Assignment.slug == slug))
    if assignment is None:
        _not_found(f"There is no assignment {slug!r} in course {code!r}.")
    require(principal, action, assignment)
    return assignment


def require_upload(session: Session, principal: Principal, slug: str) -> Problem | None:
    """Refuse (403) an upload under id ``slug`` unless it is new or names a problem the principal
    manages; returns the existing problem, if any. Call it before deriving and again before saving."""
    require(principal, Action.CREATE, None)
    existing = problem_by_slug(session, slug)
    if existing is not None and not allowed(principal, Action.MANAGE, existing):
        # The id is taken whether or not we say so (ids are unique), so this is a 403, not a 404.
        _forbidden(f"The problem id {slug!r} belongs to a course you do not teach; give the scene another id.")
    return existing


# --- lists ---------------------------------------------------------------------------------------

def visible_versions(session: Session, principal: Principal) -> list[ProblemVersion]:
    """The version of every problem the principal may see, as :func:`find_version` picks it, by title."""
    if principal.role is None:
        return []
    newest_any = _newest(published_only=False)
    newest_published = _newest(published_only=True)
    hidden = _unopened(session, principal)
    chosen: dict[int, ProblemVersion] = {}
    for query in (newest_any, newest_published):  # managed problems first: their newest, drafts too
        for version in session.scalars(query):
            if version.problem_id in chosen or (query is newest_published and version.problem_id in hidden):
                continue
            if (query is newest_any and principal.manages_course(version.problem.course_id)) or (
                    query is newest_published and allowed(principal, Action.SEE, version)):
                chosen[version.problem_id] = version
    return sorted(chosen.values(), key=lambda v: (v.title.lower(), v.id))


def _newest(*, published_only: bool):
    numbers = select(ProblemVersion.problem_id, func.max(ProblemVersion.number).label("number"))
    if published_only:
        numbers = numbers.where(ProblemVersion.published.is_(True))
    newest = numbers.group_by(ProblemVersion.problem_id).subquery()
    return (select(ProblemVersion).options(selectinload(ProblemVersion.problem))
            .join(newest, and_(ProblemVersion.problem_id == newest.c.problem_id,
                               ProblemVersion.number == newest.c.number)))


def managed_courses(session: Session, principal: Principal) -> list[Course]:
    """The courses whose problems the principal manages (every course for an admin), by code."""
    courses = session.scalars(select(Course).order_by(Course.code))
    return [c for c in courses if c.id is not None and principal.manages_course(c.id)]


def my_courses(session: Session, principal: Principal) -> list[Course]:
    """The courses the principal is enrolled in, in any role (every course for an admin), by code."""
    courses = session.scalars(select(Course).order_by(Course.code))
    return [c for c in courses if allowed(principal, Action.VIEW_COURSE, c)]


def managed_problems(session: Session, principal: Principal) -> list[Problem]:
    """The problems the principal manages, by id."""
    problems = session.scalars(select(Problem).order_by(Problem.slug))
    return [p for p in problems if allowed(principal, Action.MANAGE, p)]


# --- the principal of the current request -----------------------------------------------------------

def current_principal() -> Principal:
    """Who makes this request: the API token's user and role under ``/api/``, else the page session's
    user; anonymous if neither. Computed once per request."""
    cached = g.get("_principal")
    if cached is not None:
        return cached
    if wants_problem_json():
        user, role = g.get("api_user"), g.get("api_role")
    else:
        user = g.get("user")
        role = user.role if user is not None else None
    if user is None:
        principal = ANONYMOUS
    else:
        with db.read() as session:  # a short read of its own, like the token and session lookups
            principal = Principal.of(session, user, role)
    g._principal = principal
    return principal
