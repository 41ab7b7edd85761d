"""lagrade: grading Lagrangian-mechanics homework.

Data flows one way: scene file -> engine (``grader.mechanics``) -> stored references
-> check (``grader.answers``) -> stored verdict (``grader.store``) -> page/API/LMS (``grader.web``).
"""

__version__ = "0.1.0"
