"""Problems can be archived: ``problems.archived_at`` (null: in use). An archived problem keeps its
versions and submissions for the record, but no student sees it or answers it any more.

Revision ID: 0005
Revises: 0004
Create Date: 2026-11-23 12:00:00
"""

from typing import Sequence

import sqlalchemy as sa
from alembic import op


revision: str = '0005'
down_revision: str | Sequence[str] | None = '0004'
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None


def upgrade() -> None:
    with op.batch_alter_table('problems', schema=None) as batch_op:
        batch_op.add_column(sa.Column('archived_at', sa.DateTime(), nullable=True))


def downgrade() -> None:
    with op.batch_alter_table('problems', schema=None) as batch_op:
        batch_op.drop_column('archived_at')
