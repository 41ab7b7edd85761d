"""Derivation jobs: uploaded scenes derived by background workers, not in the request.

Revision ID: 0002
Revises: 0001
Create Date: 2026-11-23 10:50:00
"""

from typing import Sequence

import sqlalchemy as sa
from alembic import op


revision: str = '0002'
down_revision: str | Sequence[str] | None = '0001'
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None


def upgrade() -> None:
    op.create_table('derivation_jobs',
    sa.Column('id', sa.Integer(), nullable=False),
    sa.Column('requester_id', sa.Integer(), nullable=False),
    sa.Column('course_id', sa.Integer(), nullable=True),
    sa.Column('filename', sa.String(length=100), nullable=False),
    sa.Column('source', sa.Text(), nullable=False),
    sa.Column('source_sha256', sa.String(length=64), nullable=False),
    sa.Column('publish', sa.Boolean(), nullable=False),
    sa.Column('status', sa.String(length=16), nullable=False),
    sa.Column('error', sa.Text(), nullable=True),
    sa.Column('problem_version_id', sa.Integer(), nullable=True),
    sa.Column('new_version', sa.Boolean(), nullable=True),
    sa.Column('attempts', sa.Integer(), nullable=False),
    sa.Column('worker_id', sa.String(length=64), nullable=True),
    sa.Column('lease_until', sa.DateTime(), nullable=True),
    sa.Column('created_at', sa.DateTime(), nullable=False),
    sa.Column('started_at', sa.DateTime(), nullable=True),
    sa.Column('finished_at', sa.DateTime(), nullable=True),
    sa.Column('updated_at', sa.DateTime(), server_default=sa.text('(CURRENT_TIMESTAMP)'), nullable=False),
    sa.ForeignKeyConstraint(['course_id'], ['courses.id'], name=op.f('fk_derivation_jobs_course_id_courses'), ondelete='SET NULL'),
    sa.ForeignKeyConstraint(['problem_version_id'], ['problem_versions.id'], name=op.f('fk_derivation_jobs_problem_version_id_problem_versions'), ondelete='SET NULL'),
    sa.ForeignKeyConstraint(['requester_id'], ['users.id'], name=op.f('fk_derivation_jobs_requester_id_users'), ondelete='CASCADE'),
    sa.PrimaryKeyConstraint('id', name=op.f('pk_derivation_jobs'))
    )
    with op.batch_alter_table('derivation_jobs', schema=None) as batch_op:
        batch_op.create_index(batch_op.f('ix_derivation_jobs_requester_id'), ['requester_id'], unique=False)
        batch_op.create_index('ix_derivation_jobs_status_id', ['status', 'id'], unique=False)


def downgrade() -> None:
    with op.batch_alter_table('derivation_jobs', schema=None) as batch_op:
        batch_op.drop_index('ix_derivation_jobs_status_id')
        batch_op.drop_index(batch_op.f('ix_derivation_jobs_requester_id'))

    op.drop_table('derivation_jobs')
