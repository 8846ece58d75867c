-- Helpers shared by the pgTAP files, installed once in the test database by run-pgtap.sh.
CREATE SCHEMA test_helpers;

-- Runs QUERY and says how it ended (its SQLSTATE, 00000 when it succeeded) and how long it took:
-- for the cancellation tests (statement_timeout must stop a long computation promptly).
CREATE FUNCTION test_helpers.sqlstate_and_seconds(query text, OUT state text, OUT seconds double precision)
  LANGUAGE plpgsql AS $$
DECLARE
  started timestamptz := clock_timestamp();
BEGIN
  BEGIN
    EXECUTE query;
    state := '00000';
  EXCEPTION WHEN query_canceled OR others THEN  -- OTHERS alone does not catch query_canceled
    state := SQLSTATE;
  END;
  seconds := extract(epoch FROM clock_timestamp() - started);
END
$$;
