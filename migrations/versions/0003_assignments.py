"""Courses run assignments: assignments, their pinned problems, drawn parameters, and which
assignment a submission was handed in for (nullable: every existing submission stays as it was).

Revision ID: 0003
Revises: 0002
Create Date: 2026-11-23 11:11:51
"""

from typing import Sequence

import sqlalchemy as sa
from alembic import op


revision: str = '0003'
down_revision: str | Sequence[str] | None = '0002'
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None


def upgrade() -> None:
    op.create_table('assignments',
    sa.Column('id', sa.Integer(), nullable=False),
    sa.Column('course_id', sa.Integer(), nullable=False),
    sa.Column('slug', sa.String(length=64), nullable=False),
    sa.Column('title', sa.String(length=200), nullable=False),
    sa.Column('opens_at', sa.DateTime(), nullable=False),
    sa.Column('due_at', sa.DateTime(), nullable=False),
    sa.Column('closes_at', sa.DateTime(), nullable=True),
    sa.Column('time_zone', sa.String(length=64), nullable=False),
    sa.Column('max_attempts', sa.Integer(), nullable=True),
    sa.Column('late_penalty_per_day', sa.Double(), nullable=False),
    sa.Column('score_policy', sa.String(length=16), nullable=False),
    sa.Column('solutions_released', sa.Boolean(), nullable=False),
    sa.Column('created_at', sa.DateTime(), nullable=False),
    sa.ForeignKeyConstraint(['course_id'], ['courses.id'], name=op.f('fk_assignments_course_id_courses'), ondelete='CASCADE'),
    sa.PrimaryKeyConstraint('id', name=op.f('pk_assignments')),
    sa.UniqueConstraint('course_id', 'slug', name=op.f('uq_assignments_course_id_slug'))
    )
    with op.batch_alter_table('assignments', schema=None) as batch_op:
        batch_op.create_index(batch_op.f('ix_assignments_course_id'), ['course_id'], unique=False)

    op.create_table('parameter_draws',
    sa.Column('id', sa.Integer(), nullable=False),
    sa.Column('assignment_id', sa.Integer(), nullable=False),
    sa.Column('user_id', sa.Integer(), nullable=False),
    sa.Column('problem_id', sa.Integer(), nullable=False),
    sa.Column('seed', sa.Integer(), nullable=False),
    sa.Column('values', sa.JSON(), nullable=False),
    sa.Column('created_at', sa.DateTime(), nullable=False),
    sa.ForeignKeyConstraint(['assignment_id'], ['assignments.id'], name=op.f('fk_parameter_draws_assignment_id_assignments'), ondelete='CASCADE'),
    sa.ForeignKeyConstraint(['problem_id'], ['problems.id'], name=op.f('fk_parameter_draws_problem_id_problems'), ondelete='CASCADE'),
    sa.ForeignKeyConstraint(['user_id'], ['users.id'], name=op.f('fk_parameter_draws_user_id_users'), ondelete='CASCADE'),
    sa.PrimaryKeyConstraint('id', name=op.f('pk_parameter_draws')),
    sa.UniqueConstraint('assignment_id', 'user_id', 'problem_id', name=op.f('uq_parameter_draws_assignment_id_user_id_problem_id'))
    )
    with op.batch_alter_table('parameter_draws', schema=None) as batch_op:
        batch_op.create_index(batch_op.f('ix_parameter_draws_assignment_id'), ['assignment_id'], unique=False)

    op.create_table('assignment_problems',
    sa.Column('id', sa.Integer(), nullable=False),
    sa.Column('assignment_id', sa.Integer(), nullable=False),
    sa.Column('position', sa.Integer(), nullable=False),
    sa.Column('problem_id', sa.Integer(), nullable=False),
    sa.Column('problem_version_id', sa.Integer(), nullable=False),
    sa.ForeignKeyConstraint(['assignment_id'], ['assignments.id'], name=op.f('fk_assignment_problems_assignment_id_assignments'), ondelete='CASCADE'),
    sa.ForeignKeyConstraint(['problem_id'], ['problems.id'], name=op.f('fk_assignment_problems_problem_id_problems'), ondelete='CASCADE'),
    sa.ForeignKeyConstraint(['problem_version_id'], ['problem_versions.id'], name=op.f('fk_assignment_problems_problem_version_id_problem_versions')),
    sa.PrimaryKeyConstraint('id', name=op.f('pk_assignment_problems')),
    sa.UniqueConstraint('assignment_id', 'position', name=op.f('uq_assignment_problems_assignment_id_position')),
    sa.UniqueConstraint('assignment_id', 'problem_id', name=op.f('uq_assignment_problems_assignment_id_problem_id'))
    )
    with op.batch_alter_table('assignment_problems', schema=None) as batch_op:
        batch_op.create_index(batch_op.f('ix_assignment_problems_assignment_id'), ['assignment_id'], unique=False)

    # Never through batch mode on SQLite: it copies and DROPs the submissions table, and with
    # foreign keys on, the drop cascades to every verdict. SQLite adds a nullable column with its
    # reference in place.
    if op.get_bind().dialect.name == 'sqlite':
        op.execute('ALTER TABLE submissions ADD COLUMN assignment_id INTEGER '
                   'CONSTRAINT fk_submissions_assignment_id_assignments '
                   'REFERENCES assignments (id) ON DELETE SET NULL')
    else:
        op.add_column('submissions', sa.Column('assignment_id', sa.Integer(), nullable=True))
        op.create_foreign_key(op.f('fk_submissions_assignment_id_assignments'), 'submissions', 'assignments',
                              ['assignment_id'], ['id'], ondelete='SET NULL')
    op.create_index(op.f('ix_submissions_assignment_id'), 'submissions', ['assignment_id'], unique=False)


def downgrade() -> None:
    op.drop_index(op.f('ix_submissions_assignment_id'), table_name='submissions')
    if op.get_bind().dialect.name == 'sqlite':
        # SQLite cannot drop a referencing column in place; batch mode copies the table (with
        # foreign keys on, that drop cascades to verdicts: downgrade an emptied database only).
        with op.batch_alter_table('submissions', schema=None) as batch_op:
            batch_op.drop_column('assignment_id')
    else:
        op.drop_constraint(op.f('fk_submissions_assignment_id_assignments'), 'submissions', type_='foreignkey')
        op.drop_column('submissions', 'assignment_id')

    with op.batch_alter_table('assignment_problems', schema=None) as batch_op:
        batch_op.drop_index(batch_op.f('ix_assignment_problems_assignment_id'))

    op.drop_table('assignment_problems')
    with op.batch_alter_table('parameter_draws', schema=None) as batch_op:
        batch_op.drop_index(batch_op.f('ix_parameter_draws_assignment_id'))

    op.drop_table('parameter_draws')
    with op.batch_alter_table('assignments', schema=None) as batch_op:
        batch_op.drop_index(batch_op.f('ix_assignments_course_id'))

    op.drop_table('assignments')