# The image of every lagrade service in docker-compose.yml (web, worker, migrate).
FROM python:3.11-slim
WORKDIR /app
COPY pyproject.toml README.md alembic.ini ./
COPY grader ./grader
COPY migrations ./migrations
COPY problems ./problems
RUN pip install --no-cache-dir -e '.[deploy]'
RUN useradd --create-home lagrade && chown -R lagrade /app
USER lagrade
EXPOSE 8000
CMD ["gunicorn", "-w", "4", "-b", "0.0.0.0:8000", "grader.web.wsgi:app"]
